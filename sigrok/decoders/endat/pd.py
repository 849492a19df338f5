##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

import cmath
import math

import sigrokdecode as srd
from encoder_line import (Common, record_clocked, clocked_frames, crc, msb_first, lsb_first,
                          bit_string)

CLK, DATA = 0, 1

(A_BIT, A_MODE, A_START, A_F1, A_F2, A_POS, A_CRC, A_AD, A_BLOCK, A_ACK,
 A_FRAME, A_ERROR) = range(12)

# Appendix A4: five flip-flops preset to 1; the shift code feeds the
# inverted-input bit into ff0, ff1 and ff3 (x^5 + x^3 + x + 1); the code
# is read out inverted, ff4 first.
CRC_WIDTH, CRC_POLY, CRC_PRESET = 5, 0x0B, 0x1F

# Section 2.3.2.1: mode bits -> (name, type, layout).
# Layouts: pos21, pos22, block22 (pos22 then the master's block),
# param21 (the master's block, then the encoder's acknowledgement), test21.
MODES = {
    '000111': ('Encoder send position values', '2.1', 'pos21'),
    '001110': ('Selection of memory area', '2.1', 'param21'),
    '011100': ('Encoder receive parameters', '2.1', 'param21'),
    '100011': ('Encoder send parameters', '2.1', 'param21'),
    '101010': ('Encoder receive reset', '2.1', 'param21'),
    '010101': ('Encoder send test values', '2.1', 'test21'),
    '110001': ('Encoder receive test command', '2.1', 'param21'),
    '111000': ('Encoder send position values with additional data', '2.2',
               'pos22'),
    '001001': ('Encoder send position values and selection of memory area',
               '2.2', 'block22'),
    '011011': ('Encoder send position values and receive parameter', '2.2',
               'block22'),
    '100100': ('Encoder send position values and send parameter', '2.2',
               'block22'),
    '110110': ('Encoder send position values and receive test command',
               '2.2', 'block22'),
    '101101': ('Encoder send position values and receive error reset', '2.2',
               'block22'),
    '010010': ('Encoder receive communication command', '2.2', 'param21'),
}
SELECT_22 = '001001'
# Send position values and receive / send parameter.
PARAMETER_22 = ('011011', '100100')
RESET_21 = '101010'
# Commands whose acknowledgement echoes the parameter as well as the
# address (a read returns the memory's content instead).
ECHOES_PARAMETER = ('001110', '011100', '101010', '110001', '010010')

BLOCK_BITS = 8 + 16 + CRC_WIDTH
AD_BITS = 24 + CRC_WIDTH
TEST_BITS = 40
# Additional data: I[4:0] that mean NOP (type IV) and "invalid selection"
# (type III), appendix A2 4.2.3 / 4.2.4.
AD1_NOP, AD2_NOP = 0, 16
AD1_INVALID, AD2_INVALID = 15, 31
# I[4:0] of additional datum 1 that acknowledge (section 2.4.2.2).
AD1_ACK_LSB, AD1_ACK_MRS = 5, 7
# MRS codes that select additional data 1 (0x40..0x4E; 0x4F stops it) and
# 2 (0x50..0x5E; 0x5F stops it): I = MRS - 0x40 (section 2.4.2.2).
MRS_AD1, MRS_AD1_STOP, MRS_AD2_FIRST, MRS_AD2_STOP = 0x40, 0x4F, 0x50, 0x5F
# Cable delay the decoder follows after the last clock, in high phases
# (16 MHz over 100 m is a 1 us round trip, 32 high phases).
LINGER_PHASES = 64
# At most 7 low bits between values with a continuous clock (2.3.1.1),
# plus the start bit and a margin of one.
CONTINUOUS_GAP_BITS = 9


def norm_crc(bits):
    return crc(bits, CRC_WIDTH, CRC_POLY, CRC_PRESET) ^ ((1 << CRC_WIDTH) - 1)


class Decoder(Common, srd.Decoder):
    api_version = 3
    id = 'endat'
    name = 'EnDat'
    longname = 'EnDat 2.1 / 2.2'
    desc = 'HEIDENHAIN EnDat 2.1 / 2.2 encoder interface.'
    license = 'mit'
    inputs = ['logic']
    outputs = []
    tags = ['Embedded/industrial']
    channels = (
        {'id': 'clk', 'name': 'CLK', 'desc': 'Clock (at the master)'},
        {'id': 'data', 'name': 'DATA', 'desc': 'Data (at the master)'},
    )
    options = (
        {'id': 'pos_bits', 'desc': 'Position bits (word 13 of the '
         'manufacturer parameters)', 'default': 25},
        {'id': 'ad1', 'desc': 'Additional datum 1 selected before the '
         'capture (I code 0..14, -1 none)', 'default': -1},
        {'id': 'ad2', 'desc': 'Additional datum 2 selected before the '
         'capture (I code 16..23, -1 none)', 'default': -1},
    )
    FRAME_ANNOTATION = A_FRAME
    annotations = (
        ('bit', 'Bit'),
        ('mode', 'Mode command'),
        ('start', 'Start bit'),
        ('f1', 'F1'),
        ('f2', 'F2'),
        ('position', 'Position'),
        ('crc', 'CRC'),
        ('ad', 'Additional datum'),
        ('block', "Master's block"),
        ('ack', 'Acknowledgement'),
        ('frame', 'Frame'),
        ('error', 'Error'),
    )
    annotation_rows = (
        ('bits', 'Bits', (A_BIT,)),
        ('fields', 'Fields', (A_MODE, A_START, A_F1, A_F2, A_POS, A_CRC,
                              A_AD, A_BLOCK, A_ACK)),
        ('frames', 'Frames', (A_FRAME,)),
        ('errors', 'Errors', (A_ERROR,)),
    )

    def reset(self):
        self.samplerate = None


    def decode(self):
        self.pos_bits = self.options['pos_bits']
        if not 1 <= self.pos_bits <= 64:
            raise ValueError('endat: option pos_bits must be 1 to 64')
        ad1, ad2 = self.options['ad1'], self.options['ad2']
        self.last_block = None
        self.ad1 = ad1 if ad1 >= 0 else None
        self.ad2 = ad2 if ad2 >= 0 else None
        for line, end in clocked_frames(self, CLK, self.record, self.partial):
            self.frame(line, end)

    def record(self, pins):
        # The frame ends when the clock stays high for two high phases;
        # the data line is read on for LINGER_PHASES more, for what a long
        # cable delivers after the last clock.
        return record_clocked(self, pins, CLK, lambda h: 2 * h + 2,
                              linger=lambda h: LINGER_PHASES * h)

    # --- one frame -----------------------------------------------------

    def frame(self, line, end):
        start = line.samples[0]
        rises = line.edges(CLK, 'r')
        self.errors = []
        self.text = []
        if len(rises) < 8:
            self.errors.append('Too few clocks for a mode command: %d rising '
                               'edges' % len(rises))
            return self.finish(start, end)
        period = (rises[-1] - rises[1]) / max(1, len(rises) - 2)
        # Mode bits: driven at F2..F7, taken at R2..R7.
        mode = [line.at(rises[k], DATA) for k in range(1, 7)]
        code = bit_string(mode)
        for k in range(1, 7):
            self.ann(rises[k] - period / 2, rises[k] + period / 2, A_BIT,
                     ['%d' % mode[k - 1]])
        name, kind, layout = MODES.get(code, (None, None, None))
        self.ann(rises[1] - period / 2, rises[6] + period / 2, A_MODE,
                 ['Mode: %s (%s)' % (name or 'unknown', code),
                  'Mode %s' % code])
        self.text.append('mode ' + code)
        if name is None:
            # The encoder answers with an error of type I: read on as
            # "Encoder send position values" to show what it sends.
            self.errors.append('Mode command %s not in the seed\'s table '
                               '(type I)' % code)
            layout = 'pos21'
        block = None
        release = 7  # index in rises of R8: the master's driver is off
        if layout == 'param21':
            block = self.master_block(line, rises[7:7 + BLOCK_BITS], period)
            if block is None:
                return self.finish(start, end)
            release = 7 + BLOCK_BITS
        if release >= len(rises):
            self.errors.append('No clocks after the master\'s bits')
            return self.finish(start, end)
        t = self.find_start(line, rises[release], end, period, rises)
        if t is None:
            return self.finish(start, end)
        if layout == 'param21':
            self.acknowledgement(line, t, period, code, block)
        elif layout == 'test21':
            self.position(line, t, period, TEST_BITS, False, 'Test values')
        else:
            twotwo = layout != 'pos21'
            t_end = self.position(line, t, period, self.pos_bits, twotwo,
                                  'Position')
            if twotwo:
                self.additional(line, t_end, period)
            else:
                self.continuous(line, t_end, end, period, rises)
        self.last_block = None
        if layout == 'block22':
            block = self.master_block(line, rises[-BLOCK_BITS:], period)
            if block is not None:
                self.last_block = (code, block[0], block[1])
                if code == SELECT_22:
                    self.select(block[0])
        if code == RESET_21:
            self.ad1 = self.ad2 = None
        self.finish(start, end)

    def finish(self, start, end):
        self.ann(start, end, A_FRAME, ['Frame: ' + '; '.join(self.text),
                                       'Frame'])
        for e in self.errors:
            self.ann(start, end, A_ERROR, ['Error: ' + e, 'Error'])

    def sample(self, line, t, period, n):
        '''n encoder bits from the one that begins near t, each read in
        the middle of its period on the encoder's clock: the rising edge
        that launched it plus the line's delay.'''
        k0 = int(round((t - self.t_start) / period))
        out = []
        for k in range(k0, k0 + n):
            ss = self.launch(k) + self.phase
            out.append(line.at(int(ss + period / 2), DATA))
            self.ann(ss, ss + period, A_BIT, ['%d' % out[-1]])
        return out

    def launch(self, k):
        '''The rising edge that launched the k-th bit after the start
        bit (extrapolated past the last clock).'''
        i = self.start_edge + k
        if i < len(self.rises):
            return self.rises[i]
        return self.rises[-1] + (i - len(self.rises) + 1) * self.period

    def grid(self, line, t, period, rises):
        '''The line delay modulo the clock period, averaged over the
        encoder's data edges (each one left a rising clock edge that
        delay ago), and the rising edge that launched the start bit.'''
        acc = 0
        e = t
        while e is not None:
            before = [r for r in rises if r <= e]
            if before:
                ref = before[-1]
                if e - ref > period:  # past the last clock
                    ref += int((e - ref) / period) * period
                acc += cmath.exp(2j * math.pi * (e - ref) / period)
            e = line.next_change(DATA, e)
        phase = (cmath.phase(acc) / (2 * math.pi)) % 1.0 if acc else 0.0
        self.phase = phase * period
        self.period = period
        self.rises = rises
        self.t_start = t
        # The launching edge: nearest to t minus the delay.
        target = t - self.phase
        self.start_edge = min(range(len(rises)),
                              key=lambda i: abs(rises[i] - target))

    def find_start(self, line, released, end, period, rises):
        '''The start bit's rising edge: the encoder drives the line low
        after the master releases it, then sends 1.'''
        low = released if line.at(released, DATA) == 0 else \
            line.next_change(DATA, released)
        if low is None:
            self.errors.append('Line not driven: the data line stays high '
                               'after the master releases it')
            return None
        t = line.next_change(DATA, low)
        if t is None or t > rises[-1]:
            self.errors.append('No start bit while the clock ran')
            return None
        self.grid(line, t, period, rises)
        delay = int(round(self.phase))
        self.ann(t, t + period, A_START,
                 ['Start bit, %d samples after the rising clock edge' % delay,
                  'Start', 'S'])
        self.text.append('delay %d' % delay)
        return t

    def position(self, line, t, period, n, twotwo, label):
        '''Start, F1, (F2), n bits LSB first, CRC; returns the end.'''
        flags = 2 if twotwo else 1
        bits = self.sample(line, t, period, 1 + flags + n + CRC_WIDTH)
        f1 = bits[1]
        self.ann(t + period, t + 2 * period, A_F1, ['F1: %d' % f1])
        if f1:
            self.errors.append('F1: error message 1 set')
        if twotwo:
            f2 = bits[2]
            self.ann(t + 2 * period, t + 3 * period, A_F2, ['F2: %d' % f2])
            if not f2:
                self.errors.append('F2: error message 2 set (active low)')
        data = bits[1 + flags:1 + flags + n]
        value = lsb_first(data)
        p0 = t + (1 + flags) * period
        self.ann(p0, p0 + n * period, A_POS,
                 ['%s: %d' % (label, value), '%d' % value])
        sent = msb_first(bits[1 + flags + n:])
        want = norm_crc(bits[1:1 + flags + n])
        c0 = p0 + n * period
        ok = sent == want
        self.ann(c0, c0 + CRC_WIDTH * period, A_CRC,
                 ['CRC: %s' % ('ok' if ok else 'bad (sent %d, computed %d)'
                               % (sent, want)), 'CRC'])
        if not ok:
            self.errors.append('CRC error: sent %d, computed %d'
                               % (sent, want))
        self.text.append('%s %d F1 %d%s CRC %s' % (
            label.lower(), value, f1, ' F2 %d' % bits[2] if twotwo else '',
            'ok' if ok else 'bad'))
        return c0 + CRC_WIDTH * period

    def additional(self, line, t, period):
        '''The selected additional data: 2 before 1, each 24 bits and a
        CRC.'''
        for which, sel in ((2, self.ad2), (1, self.ad1)):
            if sel is None:
                continue
            bits = self.sample(line, t, period, AD_BITS)
            word = msb_first(bits[:24])
            info = (word >> 16) & 0x1F
            sent = msb_first(bits[24:])
            want = norm_crc(bits[:24])
            ok = sent == want
            self.ann(t, t + AD_BITS * period, A_AD,
                     ['Additional datum %d: 0x%06x (WRN %d RM %d Busy %d '
                      'I %d, data 0x%04x), CRC %s' % (
                          which, word, word >> 23, (word >> 22) & 1,
                          (word >> 21) & 1, info, word & 0xFFFF,
                          'ok' if ok else 'bad'), 'AD%d' % which])
            self.text.append('AD%d %06x CRC %s' % (which, word,
                                                   'ok' if ok else 'bad'))
            if not ok:
                self.errors.append('AD%d CRC error: sent %d, computed %d'
                                   % (which, sent, want))
            invalid = AD1_INVALID if which == 1 else AD2_INVALID
            nop = AD1_NOP if which == 1 else AD2_NOP
            if info == invalid:
                self.errors.append('Type III: additional datum %d says its '
                                   'selection is not valid (I = %d)'
                                   % (which, info))
            elif info == nop and sel != nop:
                self.errors.append('Type IV: additional datum %d is NOP, '
                                   'I = %d is selected' % (which, sel))
            if which == 1 and self.last_block and ok and not (word >> 21) & 1:
                self.acknowledge_22(info, word & 0xFFFF)
            t += AD_BITS * period

    def acknowledge_22(self, info, data):
        '''Section 2.5.1/2.6.1: the acknowledgement of the previous frame's
        block comes in additional datum 1; checked for "Acknowledge MRS
        code" (the MRS code in the high byte) after a selection, and
        "Acknowledge memory content LSB" (the address in the high byte)
        after a parameter access.'''
        code, mrs, param = self.last_block
        if info == AD1_ACK_MRS and code == SELECT_22:
            self.judge(mrs, data >> 8, None, None)
        elif info == AD1_ACK_LSB and code in PARAMETER_22:
            self.judge(mrs, data >> 8, None, None)

    def continuous(self, line, t, end, period, rises):
        '''With a continuous clock, further values follow "Encoder send
        position values".'''
        while rises and rises[-1] > t + CONTINUOUS_GAP_BITS * period:
            nxt = line.next_change(DATA, t)
            # The line is low after the CRC; the next value's start bit
            # rises within the gap.
            if nxt is not None and line.at(nxt, DATA) == 0:
                nxt = line.next_change(DATA, nxt)
            if nxt is None or nxt > t + CONTINUOUS_GAP_BITS * period:
                break
            self.ann(nxt, nxt + period, A_START, ['Start bit', 'S'])
            t = self.position(line, nxt, period, self.pos_bits, False,
                              'Position')

    def master_block(self, line, edges, period):
        '''The master's MRS code or address, parameter and CRC, each bit
        taken at a rising edge.'''
        if len(edges) < BLOCK_BITS:
            self.errors.append("The master's block is cut: %d of %d clocks"
                               % (len(edges), BLOCK_BITS))
            return None
        bits = [line.at(r, DATA) for r in edges]
        for r, b in zip(edges, bits):
            self.ann(r - period / 2, r + period / 2, A_BIT, ['%d' % b])
        addr, param = msb_first(bits[:8]), msb_first(bits[8:24])
        sent, want = msb_first(bits[24:]), norm_crc(bits[:24])
        ok = sent == want
        self.ann(edges[0] - period / 2, edges[-1] + period / 2, A_BLOCK,
                 ['Master: MRS/address 0x%02x parameter 0x%04x, CRC %s'
                  % (addr, param, 'ok' if ok else 'bad'), 'Block'])
        self.text.append('block %02x %04x CRC %s'
                         % (addr, param, 'ok' if ok else 'bad'))
        if not ok:
            self.errors.append("CRC error in the master's block: sent %d, "
                               "computed %d" % (sent, want))
        return addr, param

    def acknowledgement(self, line, t, period, code, block):
        bits = self.sample(line, t, period, 1 + AD_BITS)[1:]
        addr, param = msb_first(bits[:8]), msb_first(bits[8:24])
        sent, want = msb_first(bits[24:]), norm_crc(bits[:24])
        ok = sent == want
        self.ann(t + period, t + (1 + AD_BITS) * period, A_ACK,
                 ['Acknowledgement: address 0x%02x data 0x%04x, CRC %s'
                  % (addr, param, 'ok' if ok else 'bad'), 'Ack'])
        self.text.append('ack %02x %04x CRC %s'
                         % (addr, param, 'ok' if ok else 'bad'))
        if not ok:
            self.errors.append('CRC error: sent %d, computed %d'
                               % (sent, want))
        if ok:  # a corrupted acknowledgement says nothing of its content
            self.judge(block[0], addr, block[1] if code in ECHOES_PARAMETER
                       else None, param)

    def judge(self, sent_addr, addr, sent_param, param):
        '''Appendix A2, type II: "the address or parameter is returned
        inverted". Each field must come back as sent or inverted; a field
        that is neither is no type II but a wrong acknowledgement.'''
        fields = [(sent_addr, addr, 0xFF)]
        if sent_param is not None:
            fields.append((sent_param, param, 0xFFFF))
        same = [got == want for want, got, _ in fields]
        inverted = [got == (~want & mask) for want, got, mask in fields]
        if not all(s or i for s, i in zip(same, inverted)):
            self.errors.append('Acknowledgement differs from the request '
                               '(sent 0x%02x, returned 0x%02x)'
                               % (sent_addr, addr))
            verdict = 'mismatch'
        elif any(inverted) and not all(same):
            self.errors.append('Type II: the address or parameter came back '
                               'inverted')
            verdict = 'type II'
        else:
            verdict = 'ok'
        self.text.append('acknowledgement ' + verdict)

    def select(self, mrs):
        '''Section 2.4.2.2: the selection holds from the next frame on.'''
        if mrs == MRS_AD1_STOP:
            self.ad1 = None
        elif MRS_AD1 <= mrs < MRS_AD1_STOP:
            self.ad1 = mrs - MRS_AD1
        elif mrs == MRS_AD2_STOP:
            self.ad2 = None
        elif MRS_AD2_FIRST <= mrs < MRS_AD2_STOP:
            self.ad2 = mrs - MRS_AD1
