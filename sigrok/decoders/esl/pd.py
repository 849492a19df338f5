##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

import sigrokdecode as srd
from encoder_line import (Common, HalfDuplex, crc, REQUEST_ANSWER_ANNOTATIONS,
                          REQUEST_ANSWER_ROWS, A_FIELD, A_REQUEST,
                          A_ANSWER, A_ERROR)

# Table 12: Data ID -> (CH1 fields after CF and SF, CH1 CRC bits,
# CH2 fields after CF2 and SF2 or None, CH2 CRC bits).
POS_SAFE = ('ALM1', 'ABS0', 'ABS1', 'ABS2', 'SC1')
CH2_SAFE = ('ALM2', 'RS0', 'RS1_SC2')
LAYOUT = {
    0x1: (('ALM1', 'ABS0', 'ABS1', 'ABS2', 'ABM0', 'ABM1', 'SC1'), 16,
          CH2_SAFE, 16),
    0x2: (POS_SAFE, 16, CH2_SAFE, 16),
    0x4: (('ABS0', 'ABS1', 'ABS2', 'ABM0', 'ABM1'), 8, None, 0),
    0x5: (('ABS0', 'ABS1', 'ABS2'), 8, None, 0),
    0x6: (('ABS0', 'ABS1', 'ABS2'), 8, ('RS0', 'RS1'), 8),
    0x8: (('ENID', 'SC1'), 16, ('ENID', 'X_SC2'), 16),
    0x9: (('TEMP',), 8, None, 0),
    0xA: (('ALM1',), 8, ('ALM2',), 8),
    0xB: (POS_SAFE, 16, CH2_SAFE, 16),
    0xC: (('ALM1', 'ABS0', 'ABS1', 'ABS2'), 8, ('ALM2', 'RS0', 'RS1'), 8),
    0xD: (('ALM1', 'ABM0', 'ABM1'), 8, None, 0),
}
MEMORY_READ, MEMORY_WRITE = 0xE, 0xF
CRC8_POLY, CRC16_POLY = 0x2F, 0x5935
CRC_PRESET = {(8, 1): 0x00, (8, 2): 0x00, (16, 1): 0x0000, (16, 2): 0xFFFF}
# Table 7: ALM bits.
ALARMS = ('XC', 'MT', 'LED/LIS', 'OVSP', 'MEM', 'ST', 'UV', 'OV')


def parse_cf(cf):
    '''(address, Data ID, parity ok: odd over the Data ID and CC4)'''
    ident = (cf >> 3) & 0xF
    return cf & 0x7, ident, (bin(ident).count('1') + (cf >> 7)) % 2 == 1


def wire_bits(values):
    return [(v >> i) & 1 for v in values for i in range(8)]


def reflect(v, width):
    return int(format(v, '0%db' % width)[::-1], 2)


def esl_crc(values, width, channel):
    '''The CRC as its bytes are sent (low byte first).'''
    if width == 16 and len(values) % 2:
        values = list(values) + [0]
    poly = CRC8_POLY if width == 8 else CRC16_POLY
    reg = crc(wire_bits(values), width, poly, CRC_PRESET[(width, channel)])
    r = reflect(reg, width)
    return [r & 0xFF] if width == 8 else [r & 0xFF, r >> 8]


def request_length(cf):
    ident = parse_cf(cf)[1]
    return {MEMORY_READ: 3, MEMORY_WRITE: 4}.get(ident, 2)


def answer_length(ident):
    if ident in (MEMORY_READ, MEMORY_WRITE):
        return 4
    if ident not in LAYOUT:
        return 0
    f1, w1, f2, w2 = LAYOUT[ident]
    n = 2 + len(f1) + w1 // 8
    if f2 is not None:
        n += 2 + len(f2) + w2 // 8
    return n


class Decoder(Common, srd.Decoder):
    api_version = 3
    id = 'esl'
    name = 'ESL'
    longname = 'ESL safety serial'
    desc = 'ESL encoder requests and answers, both channels.'
    license = 'mit'
    inputs = ['uart']
    outputs = []
    tags = ['Embedded/industrial']
    options = (
        {'id': 'timeout_us', 'desc': 'Answer timeout after a request (us)',
         'default': 5.0},
        {'id': 'broadcast_address', 'desc': 'Address every encoder obeys '
         'and none answers (-1: none)', 'default': 7},
        {'id': 'st_bits', 'desc': 'Single-turn bits in ABS0..ABS2',
         'default': 24},
        {'id': 'rs_tolerance', 'desc': 'Largest RS - ABS difference in RS '
         'steps', 'default': 1},
    )
    annotations = REQUEST_ANSWER_ANNOTATIONS
    annotation_rows = REQUEST_ANSWER_ROWS

    def reset(self):
        self.samplerate = None
        self.sequence = {}  # address -> last SC1
        self.line = HalfDuplex(
            self, request_length,
            lambda cf, request: answer_length(parse_cf(request[0][2])[1]),
            self.looks_like_request, self.expects_answer)

    def decode(self, ss, es, data):
        timeout = self.options['timeout_us'] * 1e-6
        self.line.packet(ss, es, data, int(timeout * (self.samplerate or 0)))

    def looks_like_request(self, value, valid):
        return valid and parse_cf(value)[2]

    def expects_answer(self, request):
        return parse_cf(request[0][2])[0] != self.options['broadcast_address']

    def errors_out(self, ss, es, errors):
        for e in errors:
            self.ann(ss, es, A_ERROR, ['Error: ' + e, 'Error'])

    def framing(self, msg, errors):
        for i, (ss, es, v, valid) in enumerate(msg):
            if not valid:
                errors.append('Byte %d (0x%02x): UART framing error' % (i, v))

    def cf_text(self, cf):
        address, ident, parity_ok = parse_cf(cf)
        return 'address %d, Data ID %X, parity %s' % (
            address, ident, 'ok' if parity_ok else 'bad')

    def check_crc(self, msg, width, channel, errors, name):
        n = width // 8
        values = [m[2] for m in msg]
        sent, want = values[-n:], esl_crc(values[:-n], width, channel)
        ok = sent == want
        self.ann(msg[-n][0], msg[-1][1], A_FIELD, [
            '%s: %s %s' % (name, ' '.join('%02x' % v for v in sent),
                           'ok' if ok else 'bad (computed %s)' % ' '.join(
                               '%02x' % v for v in want)), name])
        if not ok:
            errors.append('%s error: sent %s, computed %s' % (
                name, ' '.join('%02x' % v for v in sent),
                ' '.join('%02x' % v for v in want)))
        return ok

    def on_request(self, msg):
        errors = []
        self.framing(msg, errors)
        ss, es, cf, _ = msg[0]
        self.ann(ss, es, A_FIELD, ['CF: ' + self.cf_text(cf), 'CF'])
        if not parse_cf(cf)[2]:
            errors.append('CF: parity bad')
        if len(msg) >= 2:
            self.check_crc(msg, 8, 1, errors, 'CRC1')
        data = ' '.join('%02x' % m[2] for m in msg)
        self.ann(ss, msg[-1][1], A_REQUEST, ['Request: bytes %s; %s'
                                             % (data, self.cf_text(cf)),
                                             'Request'])
        self.errors_out(ss, msg[-1][1], errors)

    def on_no_answer(self, request):
        self.ann(request[0][0], request[-1][1], A_ERROR,
                 ['Error: No answer within the timeout', 'Error: no answer'])

    def on_answer(self, msg, request, late, more):
        ss, es = msg[0][0], msg[-1][1]
        data = ' '.join('%02x' % m[2] for m in msg)
        if more:
            self.ann(ss, es, A_ANSWER, ['Answer continued: bytes %s' % data,
                                        'More'])
            self.errors_out(ss, es, ['Answer of more bytes than its Data ID '
                                     'has'])
            return
        errors = []
        if late:
            errors.append('No answer within the timeout (this one comes '
                          'late)')
        self.framing(msg, errors)
        values = [m[2] for m in msg]
        want_cf = request[0][2] if request else None
        if want_cf is not None and values[0] != want_cf:
            errors.append('CF 0x%02x differs from the request\'s 0x%02x'
                          % (values[0], want_cf))
        _, ident, _ = parse_cf(want_cf if want_cf is not None else values[0])
        want = answer_length(ident)
        text = []
        if want and len(msg) != want:
            errors.append('Answer of %d bytes, Data ID %X has %d'
                          % (len(msg), ident, want))
        if not want or len(msg) < 3:
            pass
        elif ident in (MEMORY_READ, MEMORY_WRITE):
            adf, edf = values[1], values[2]
            self.ann(msg[1][0], msg[1][1], A_FIELD, [
                'ADF: address 0x%02x, busy %d' % (adf >> 1, adf & 1), 'ADF'])
            self.ann(msg[2][0], msg[2][1], A_FIELD, ['EDF: 0x%02x' % edf,
                                                     'EDF'])
            ok = self.check_crc(msg, 8, 1, errors, 'CRC1')
            text.append('ADF %02x busy %d EDF %02x CRC1 %s'
                        % (adf >> 1, adf & 1, edf, 'ok' if ok else 'bad'))
        else:
            text += self.two_channels(msg, ident, errors, len(msg) == want)
        self.ann(ss, es, A_ANSWER, ['Answer: bytes %s; %s' % (
            data, ', '.join(text)), 'Answer'])
        self.errors_out(ss, es, errors)

    def two_channels(self, msg, ident, errors, whole):
        '''Both channels by the Data ID's layout, over the bytes there
        are: a channel cut short has no CRC to check.'''
        f1, w1, f2, w2 = LAYOUT[ident]
        n1 = 2 + len(f1) + w1 // 8
        if len(msg) < n1:
            errors.append('CRC1 error: CH1 cut at %d of %d bytes'
                          % (len(msg), n1))
            if f2 is not None:
                errors.append('CRC2 error: CH2 missing')
            return []
        ch1 = self.channel(msg[:n1], f1, w1, 1, errors)
        text = ['CH1 ' + ch1.pop('text')]
        if f2 is None:
            return text
        n2 = 2 + len(f2) + w2 // 8
        if len(msg) < n1 + n2:
            errors.append('CRC2 error: CH2 cut at %d of %d bytes'
                          % (len(msg) - n1, n2))
            return text
        ch2 = self.channel(msg[n1:n1 + n2], f2, w2, 2, errors)
        text.append('CH2 ' + ch2.pop('text'))
        if ch2['CF'] != ch1['CF']:
            errors.append('CF2 0x%02x differs from CF 0x%02x'
                          % (ch2['CF'], ch1['CF']))
        address = parse_cf(ch1['CF'])[0]
        judge = ch1['ok'] and ch2['ok'] and whole
        for key, ch, mod in (('SC1', ch1, 256), ('SC2', ch2, 128)):
            if key in ch:
                last = self.sequence.get((address, key))
                if judge and last is not None and ch[key] != (last + 1) % mod:
                    errors.append('Sequence: %s %d after %d'
                                  % (key, ch[key], last))
                self.sequence[(address, key)] = ch[key]
        if not judge:
            # Corrupted fields, or an answer of the wrong length, say
            # nothing of the channels.
            return text
        disagree = []
        if 'ALM1' in ch1 and 'ALM2' in ch2 and ch1['ALM1'] != ch2['ALM2']:
            disagree.append('ALM1 %02x ALM2 %02x' % (ch1['ALM1'],
                                                     ch2['ALM2']))
        if 'RS' in ch2 and 'ABS' in ch1:
            # RS: the single turn again at 9 bits (the seed's "9bit
            # resolution of ST2") or extended to 16, against ABS's top
            # bits, modulo a turn.
            bits = 9 if ch2['RS9'] else 16
            top = ch1['ABS'] >> (self.options['st_bits'] - bits)
            delta = (ch2['RS'] - top) % (1 << bits)
            if min(delta, (1 << bits) - delta) > self.options['rs_tolerance']:
                disagree.append('RS %d, ABS gives %d' % (ch2['RS'], top))
        if disagree:
            errors.append('Channels disagree: ' + ', '.join(disagree))
        return text

    def channel(self, msg, names, width, channel, errors):
        values = [m[2] for m in msg]
        out = {'CF': values[0]}
        ss, es = msg[1][0], msg[1][1]
        sf = values[1]
        self.ann(ss, es, A_FIELD, ['SF%s: CA %d%d EA %d%d DD %d%d%d%d' % (
            '' if channel == 1 else '2', sf & 1, sf >> 1 & 1, sf >> 2 & 1,
            sf >> 3 & 1, sf >> 4 & 1, sf >> 5 & 1, sf >> 6 & 1, sf >> 7 & 1),
            'SF'])
        alarm = sf & 0x3
        for name, (ss, es, v, _) in zip(names, msg[2:2 + len(names)]):
            if name == 'RS1_SC2':
                out['RS1'], out['SC2'] = v & 1, v >> 1
            elif name == 'X_SC2':
                out['SC2'] = v >> 1
            else:
                out[name] = v
            self.ann(ss, es, A_FIELD, ['%s: 0x%02x' % (name, v), name])
        ok = self.check_crc(msg, width, channel, errors, 'CRC%d' % channel)
        out['ok'] = ok
        if ok and alarm:
            errors.append('Communication alarm (CH%d): CA0 %d CA1 %d'
                          % (channel, sf & 1, sf >> 1 & 1))
        parts = ['SF %02x' % sf]
        if all('ABS%d' % i in out for i in range(3)):
            out['ABS'] = sum(out['ABS%d' % i] << 8 * i for i in range(3))
            parts.append('ABS %d' % out['ABS'])
        if 'ABM0' in out:
            parts.append('ABM %d' % (out['ABM0'] | out['ABM1'] << 8))
        if 'RS0' in out:
            # With SC2 beside it RS is 9 bits (RS0 bits 8..1, RS1 bit 0);
            # Data ID 6 and C send it extended, RS0 high byte.
            out['RS9'] = 'SC2' in out
            out['RS'] = (out['RS0'] << 1 | out['RS1']) if out['RS9'] else \
                (out['RS0'] << 8 | out['RS1'])
            parts.append('RS %d' % out['RS'])
        for key in ('ALM1', 'ALM2', 'SC1', 'SC2', 'ENID', 'TEMP'):
            if key in out:
                parts.append('%s %d' % (key, out[key]))
        parts.append('CRC%d %s' % (channel, 'ok' if ok else 'bad'))
        out['text'] = ' '.join(parts)
        return out
