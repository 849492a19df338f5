##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

import sigrokdecode as srd
from encoder_line import (Common, record_clocked, clocked_frames, crc, msb_first,
                          bit_string)

MA, SLO = 0, 1

(A_BIT, A_ACK, A_START, A_CDS, A_DATA, A_NE, A_NW, A_CRC, A_CDM, A_FRAME,
 A_CONTROL, A_ERROR) = range(12)

# The seed's CRC: g(x) = x^6 + x + 1, preset 0 (the seed's worked example
# 1000101011100011 1 0 -> 110101 holds with preset 0, not with all ones),
# sent inverted.
SEED_CRC_POLY = 0x03
# The control frame's CRC-4, x^4 + x + 1, preset 0, sent inverted (BiSS C
# register access; the seed does not describe control frames).
CONTROL_CRC_WIDTH, CONTROL_CRC_POLY = 4, 0x03
# CDM zeros that announce a control frame.
CONTROL_IDLE_ZEROS = 14


def ints(text, name, base=10):
    try:
        return [int(x, base) for x in str(text).split('/') if x.strip()]
    except ValueError:
        raise ValueError('biss_c: option %s must be numbers separated by /, '
                         'got %r' % (name, text))


class Decoder(Common, srd.Decoder):
    api_version = 3
    id = 'biss_c'
    name = 'BiSS-C'
    longname = 'BiSS-C absolute encoder'
    desc = 'BiSS-C position frames, CRC and register access.'
    license = 'mit'
    inputs = ['logic']
    outputs = []
    tags = ['Embedded/industrial']
    channels = (
        {'id': 'ma', 'name': 'MA', 'desc': 'Master clock (at the master)'},
        {'id': 'slo', 'name': 'SLO', 'desc': 'Slave data (at the master)'},
    )
    options = (
        {'id': 'bits', 'desc': 'Data bits per slave (e.g. 16 or 12/25/32)',
         'default': '16'},
        {'id': 'crc_bits', 'desc': 'CRC bits per slave', 'default': '6'},
        {'id': 'crc_poly', 'desc': 'CRC polynomials per slave (hex, '
         'without the top term)', 'default': '0x03'},
    )
    FRAME_ANNOTATION = A_FRAME
    annotations = (
        ('bit', 'Bit'),
        ('ack', 'Acknowledge'),
        ('start', 'Start bit'),
        ('cds', 'CDS'),
        ('data', 'Data'),
        ('ne', 'nE'),
        ('nw', 'nW'),
        ('crc', 'CRC'),
        ('cdm', 'CDM'),
        ('frame', 'Frame'),
        ('control', 'Control frame'),
        ('error', 'Error'),
    )
    annotation_rows = (
        ('bits', 'Bits', (A_BIT,)),
        ('fields', 'Fields', (A_ACK, A_START, A_CDS, A_DATA, A_NE, A_NW,
                              A_CRC, A_CDM)),
        ('frames', 'Frames', (A_FRAME,)),
        ('control', 'Control frames', (A_CONTROL,)),
        ('errors', 'Errors', (A_ERROR,)),
    )

    def reset(self):
        self.samplerate = None
        self.control = []  # (ss, es, cdm, [cds per slave]) per frame
        # After a control frame's stop bit a new start bit may follow
        # without the idle run.
        self.chained = False


    def slaves(self):
        bits = ints(self.options['bits'], 'bits')
        widths = ints(self.options['crc_bits'], 'crc_bits')
        polys = ints(self.options['crc_poly'], 'crc_poly', 16)
        n = len(bits)
        if not n or len(widths) not in (1, n) or len(polys) not in (1, n):
            raise ValueError('biss_c: give one CRC width and polynomial, or '
                             'one per slave (%d slaves in option bits)' % n)
        widths = widths * n if len(widths) == 1 else widths
        polys = polys * n if len(polys) == 1 else polys
        return list(zip(bits, widths, polys))

    def decode(self):
        slaves = self.slaves()
        # A frame ends when MA rests (at either level: the CDM) for four
        # of its phases.
        record = lambda pins: record_clocked(  # noqa: E731
            self, pins, MA, lambda p: 4 * p + 2, either=True)
        for line, end in clocked_frames(self, MA, record, self.partial):
            self.frame(line, end, slaves)

    def frame(self, line, end, slaves):
        start = line.samples[0]
        rises = line.edges(MA, 'r')
        errors = []
        result = {'ss': start, 'es': end}
        if line.at(start, SLO) == 0:
            self.ann(start, end, A_ERROR, ['Warning: SLO low at the start '
                                           '(slave busy or line stuck low)',
                                           'Warning: SLO low'])
        if len(rises) < 3:
            errors.append('Too few clocks: %d rising MA edges' % len(rises))
            return self.finish(line, start, end, [], errors, None)
        period = (rises[-1] - rises[0]) / (len(rises) - 1)
        ack_at = line.next_change(SLO, rises[1]) if line.at(rises[1], SLO) else rises[1]
        if ack_at is None or ack_at > rises[-1] + period:
            errors.append('No acknowledge: SLO stays high')
            return self.finish(line, start, end, [], errors, None)
        delay = ack_at - rises[1]
        self.ann(rises[1], ack_at, A_ACK, ['Delay: %d' % delay,
                                           'Line delay %d samples' % delay])

        # Bit k was launched at rising edge k and is read in the middle of
        # its period, after the line delay.
        def span(k):
            return (rises[k] + delay, rises[k] + delay + int(period))

        def level(k):
            return line.at(rises[k] + delay + int(period / 2), SLO)

        k = 1
        while k < len(rises) and level(k) == 0:
            k += 1
        self.ann(span(1)[0], span(k - 1)[1] if k > 1 else span(1)[1], A_ACK,
                 ['Acknowledge', 'Ack', 'A'])
        if k >= len(rises):
            errors.append('No start bit')
            return self.finish(line, start, end, [], errors, None)
        self.ann(*span(k), A_START, ['Start', 'S'])
        bits = [1]
        pos = k + 1
        sections = []
        for index, (width, crc_width, poly) in enumerate(slaves):
            need = 1 + width + 2 + crc_width
            if pos + need > len(rises):
                errors.append('Frame cut: slave %d needs %d more clocks'
                              % (index, pos + need - len(rises)))
                break
            b = [level(j) for j in range(pos, pos + need)]
            for j, v in enumerate(b):
                self.ann(*span(pos + j), A_BIT, ['%d' % v])
            bits += b
            cds, data = b[0], b[1:1 + width]
            ne, nw = b[1 + width], b[2 + width]
            sent = msb_first(b[3 + width:])
            want = crc(data + [ne, nw], crc_width, poly, 0) ^ ((1 << crc_width) - 1)
            value = msb_first(data)
            self.ann(*span(pos), A_CDS, ['CDS: %d' % cds])
            self.ann(span(pos + 1)[0], span(pos + width)[1], A_DATA,
                     ['Position: %d' % value, 'Pos: %d' % value])
            self.ann(*span(pos + 1 + width), A_NE,
                     ['Error: %s' % ('no' if ne else 'yes'), 'nE: %d' % ne])
            self.ann(*span(pos + 2 + width), A_NW,
                     ['Warning: %s' % ('no' if nw else 'yes'), 'nW: %d' % nw])
            ok = sent == want
            self.ann(span(pos + 3 + width)[0], span(pos + need - 1)[1], A_CRC,
                     ['CRC: %s' % ('ok' if ok else 'bad (sent 0x%x, computed '
                      '0x%x)' % (sent, want)), 'CRC'])
            if not ok:
                errors.append('CRC error slave %d: sent 0x%x, computed 0x%x'
                              % (index, sent, want))
            sections.append((index, value, ne, nw, cds, ok))
            pos += need
        cdm = 1 - line.at(end, MA) if line.at(end, MA) == 0 else 0
        self.ann(end, end + int(period), A_CDM, ['CDM: %d' % cdm])
        return self.finish(line, start, end, sections, errors, cdm, bits)

    def finish(self, line, start, end, sections, errors, cdm, bits=()):
        parts = ['slave %d position %d nE %d nW %d CDS %d CRC %s'
                 % (i, v, ne, nw, cds, 'ok' if ok else 'bad')
                 for i, v, ne, nw, cds, ok in sections]
        text = 'Frame: ' + ('; '.join(parts) if parts else 'no data')
        if cdm is not None:
            text += '; CDM %d' % cdm
        if bits:
            text += '; bits ' + bit_string(bits)
        self.ann(start, end, A_FRAME, [text, 'Frame'])
        for e in errors:
            self.ann(start, end, A_ERROR, ['Error: ' + e, 'Error'])
        if cdm is None:
            self.control = []
            return
        self.control.append((start, end, cdm, [s[4] for s in sections]))
        self.control_frame()

    def control_frame(self):
        '''Register access from the CDM/CDS bits of the frames so far.'''
        cdm = [c[2] for c in self.control]
        zeros = 0
        for i, b in enumerate(cdm):
            if b == 0:
                zeros += 1
                continue
            if zeros < CONTROL_IDLE_ZEROS and not self.chained:
                # A 1 without the idle run before it: not a control frame.
                self.control = self.control[i + 1:]
                return
            first = i
            break
        else:
            # Keep only the idle run that may still announce a frame.
            self.control = self.control[-CONTROL_IDLE_ZEROS:]
            if zeros >= CONTROL_IDLE_ZEROS:
                self.chained = False
            return
        body = cdm[first:]
        if len(body) < 2:
            return
        cts = body[1]
        if cts == 1:
            total = 1 + 1 + 3 + 7 + 4 + 2 + 1 + 8 + 4 + 1
            if len(body) < total + 1:  # and the frame that carries the last CDS
                return
            self.register_frame(first, total)
            self.chained = True
        else:
            total = 1 + 1 + 8 + 2 + 4
            if len(body) < total:
                return
            self.command_frame(first, total)
            self.control = []
            self.chained = False
            return
        self.control = self.control[first + total:]

    def command_frame(self, first, total):
        '''S, CTS = 0, the 8 ID-select bits, a 2-bit command, CRC-4 over
        CTS, IDS and command.'''
        frames = self.control[first:first + total]
        cdm = [f[2] for f in frames]
        ids = msb_first(cdm[2:10])
        code = msb_first(cdm[10:12])
        inv = (1 << CONTROL_CRC_WIDTH) - 1
        ok = msb_first(cdm[12:16]) == crc(cdm[1:12], CONTROL_CRC_WIDTH,
                                          CONTROL_CRC_POLY, 0) ^ inv
        self.ann(frames[0][0], frames[-1][1], A_CONTROL,
                 ['Control: Command: IDS 0x%02x code %d, CRC %s'
                  % (ids, code, 'ok' if ok else 'bad'), 'Command %d' % code])

    def register_frame(self, first, total):
        frames = self.control[first:first + total]
        cdm = [f[2] for f in frames]
        ident = msb_first(cdm[2:5])
        addr = msb_first(cdm[5:12])
        crc_sent = msb_first(cdm[12:16])
        inv = (1 << CONTROL_CRC_WIDTH) - 1
        # The address CRC covers CTS, ID and address.
        crc_want = crc(cdm[1:12], CONTROL_CRC_WIDTH, CONTROL_CRC_POLY, 0) ^ inv
        read, write = cdm[16], cdm[17]
        data_at = 19
        if write and not read:
            src = cdm
            who = 'write'
        else:
            who = 'read'
            # A slave answers a CDM bit with its CDS bit in the next frame.
            src = [f[3][ident] if ident < len(f[3]) else 0
                   for f in self.control[first + 1:first + total + 1]]
        data = msb_first(src[data_at:data_at + 8])
        dcrc = msb_first(src[data_at + 8:data_at + 12])
        dcrc_want = crc(src[data_at:data_at + 8], CONTROL_CRC_WIDTH,
                        CONTROL_CRC_POLY, 0) ^ inv
        text = ('Register %s: ID %d address 0x%02x data 0x%02x, address CRC '
                '%s, data CRC %s' % (who, ident, addr, data,
                                     'ok' if crc_sent == crc_want else 'bad',
                                     'ok' if dcrc == dcrc_want else 'bad'))
        self.ann(frames[0][0], frames[-1][1], A_CONTROL,
                 ['Control: ' + text, 'Register %s' % who])
