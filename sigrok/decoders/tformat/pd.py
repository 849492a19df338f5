##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

import sigrokdecode as srd
from encoder_line import (Common, HalfDuplex, REQUEST_ANSWER_ANNOTATIONS,
                          REQUEST_ANSWER_ROWS, A_FIELD, A_REQUEST,
                          A_ANSWER, A_ERROR)

SINK_CODE = 0b010
# Table 1: Data ID -> application; the request's and answer's fields
# (table 2; EEPROM access 6.2.2 / 6.2.3).
READOUT = (0x0, 0x1, 0x2, 0x3)
RESETS = (0x7, 0x8, 0xC)
EEPROM_WRITE, EEPROM_READ = 0x6, 0xD
DATA_FIELDS = {0x0: ('ABS0', 'ABS1', 'ABS2'), 0x1: ('ABM0', 'ABM1', 'ABM2'),
               0x2: ('ENID',),
               0x3: ('ABS0', 'ABS1', 'ABS2', 'ENID', 'ABM0', 'ABM1', 'ABM2',
                     'ALMC'),
               0x7: ('ABS0', 'ABS1', 'ABS2'), 0x8: ('ABS0', 'ABS1', 'ABS2'),
               0xC: ('ABS0', 'ABS1', 'ABS2')}
# Table 3: ALMC bits d70..d77 (d74 is always 0).
ALMC = ('OS', 'FS', 'CE', 'OF', None, 'ME', 'BE', 'BA')
# An abnormal request or a communication alarm gets Data ID 3's fields.
ABNORMAL_ANSWER_ID = 0x3


def parse_cf(cf):
    '''(sink code, Data ID, parity ok)'''
    sink = cf & 0x7
    ident = (cf >> 3) & 0xF
    parity = (cf >> 7) & 1
    return sink, ident, parity == bin(ident).count('1') % 2


def request_length(ident):
    return {EEPROM_WRITE: 4, EEPROM_READ: 3}.get(ident, 1)


def answer_length(ident):
    if ident in (EEPROM_WRITE, EEPROM_READ):
        return 4
    fields = DATA_FIELDS.get(ident, DATA_FIELDS[ABNORMAL_ANSWER_ID])
    return 2 + len(fields) + 1


def looks_like_request(value, valid):
    sink, _, parity_ok = parse_cf(value)
    return valid and sink == SINK_CODE and parity_ok


def xor(bs):
    v = 0
    for b in bs:
        v ^= b
    return v


class Decoder(Common, srd.Decoder):
    api_version = 3
    id = 'tformat'
    name = 'T-format'
    longname = 'Tamagawa T-format'
    desc = 'Tamagawa Smart Abs T-format requests and answers.'
    license = 'mit'
    inputs = ['uart']
    outputs = []
    tags = ['Embedded/industrial']
    options = (
        {'id': 'timeout_us', 'desc': 'Answer timeout after a request (us)',
         'default': 10.0},
    )
    annotations = REQUEST_ANSWER_ANNOTATIONS
    annotation_rows = REQUEST_ANSWER_ROWS

    def reset(self):
        self.samplerate = None
        self.request_cf = None
        self.want_answer = None
        self.line = HalfDuplex(
            self, lambda cf: request_length(parse_cf(cf)[1]),
            lambda cf, request: answer_length(parse_cf(request[0][2])[1]),
            looks_like_request, lambda request: True)

    def decode(self, ss, es, data):
        timeout = self.options['timeout_us'] * 1e-6
        self.line.packet(ss, es, data, int(timeout * (self.samplerate or 0)))

    def on_no_answer(self, request):
        self.ann(request[0][0], request[-1][1], A_ERROR,
                 ['Error: No answer within the timeout', 'Error: no answer'])

    def on_request(self, msg):
        self.request(msg)

    def on_answer(self, msg, request, late, more):
        ss, es = msg[0][0], msg[-1][1]
        if more:
            self.ann(ss, es, A_ANSWER, ['Answer continued: bytes %s' % ' '.join(
                '%02x' % m[2] for m in msg), 'More'])
            self.ann(ss, es, A_ERROR, ['Error: Answer of more bytes than its '
                                       'Data ID has', 'Error: too long'])
            return
        if late:
            self.ann(ss, es, A_ERROR, ['Error: No answer within the timeout '
                                       '(this one comes late)', 'Error: late'])
        self.answer(msg)

    def common(self, msg, errors):
        '''CF annotation and framing checks; returns the Data ID.'''
        for i, (ss, es, value, valid) in enumerate(msg):
            if not valid:
                errors.append('Byte %d (0x%02x): UART framing error '
                              '(start bit or delimiter)' % (i, value))
        ss, es, cf, _ = msg[0]
        sink, ident, parity_ok = parse_cf(cf)
        self.ann(ss, es, A_FIELD, ['CF: sink %d%d%d, Data ID %X, parity %s'
                                   % (sink & 1, (sink >> 1) & 1, sink >> 2,
                                      ident, 'ok' if parity_ok else 'bad'),
                                   'CF %X' % ident])
        if sink != SINK_CODE:
            errors.append('CF: sink code is not 010')
        if not parity_ok:
            errors.append('CF: ID parity bad')
        return ident

    def finish(self, cls, msg, kind, ident, text, errors):
        ss, es = msg[0][0], msg[-1][1]
        data = ' '.join('%02x' % m[2] for m in msg)
        self.ann(ss, es, cls, ['%s: Data ID %X, bytes %s%s' % (
            kind, ident, data, '; ' + text if text else ''), kind])
        for e in errors:
            self.ann(ss, es, A_ERROR, ['Error: ' + e, 'Error'])

    def request(self, msg):
        errors = []
        ident = self.common(msg, errors)
        self.request_cf = msg[0][2]
        self.want_answer = answer_length(ident)
        text = ''
        if ident in (EEPROM_WRITE, EEPROM_READ):
            text = self.eeprom(msg, errors, ident == EEPROM_WRITE)
        self.finish(A_REQUEST, msg, 'Request', ident, text, errors)

    def answer(self, msg):
        errors = []
        ident = self.common(msg, errors)
        if self.request_cf is not None and msg[0][2] != self.request_cf:
            errors.append('CF 0x%02x differs from the request\'s 0x%02x'
                          % (msg[0][2], self.request_cf))
        if self.request_cf is not None and len(msg) != self.want_answer:
            errors.append('Answer of %d bytes, the request asks for %d'
                          % (len(msg), self.want_answer))
        if ident in (EEPROM_WRITE, EEPROM_READ):
            text = self.eeprom(msg, errors, True)
        else:
            text = self.readout(msg, errors, ident)
        self.finish(A_ANSWER, msg, 'Answer', ident, text, errors)

    def crc(self, msg, errors, want_len):
        if len(msg) < want_len:
            errors.append('CRC error: cut at %d of %d bytes'
                          % (len(msg), want_len))
            return 'CRC missing'
        msg = msg[:want_len]
        body, sent = [m[2] for m in msg[:-1]], msg[-1][2]
        want = xor(body)
        ss, es = msg[-1][0], msg[-1][1]
        ok = sent == want
        self.ann(ss, es, A_FIELD, ['CRC: 0x%02x %s' % (sent, 'ok' if ok else
                                   'bad (computed 0x%02x)' % want), 'CRC'])
        if not ok:
            errors.append('CRC error: sent 0x%02x, computed 0x%02x'
                          % (sent, want))
        return 'CRC ' + ('ok' if ok else 'bad')

    def eeprom(self, msg, errors, has_edf):
        parts = []
        if len(msg) > 1:
            ss, es, adf, _ = msg[1]
            self.ann(ss, es, A_FIELD, ['ADF: address %d, busy %d'
                                       % (adf & 0x7F, adf >> 7), 'ADF'])
            parts.append('ADF %d busy %d' % (adf & 0x7F, adf >> 7))
        if has_edf and len(msg) > 2:
            ss, es, edf, _ = msg[2]
            self.ann(ss, es, A_FIELD, ['EDF: 0x%02x' % edf, 'EDF'])
            parts.append('EDF %02x' % edf)
        parts.append(self.crc(msg, errors, 4 if has_edf else 3))
        return ', '.join(parts)

    def readout(self, msg, errors, ident):
        parts = []
        if len(msg) > 1:
            ss, es, sf, _ = msg[1]
            ea0, ea1 = sf >> 4 & 1, sf >> 5 & 1
            ca0, ca1 = sf >> 6 & 1, sf >> 7 & 1
            self.ann(ss, es, A_FIELD, ['SF: ea0 %d ea1 %d ca0 %d ca1 %d'
                                       % (ea0, ea1, ca0, ca1), 'SF'])
            parts.append('SF %02x' % sf)
            if ca0 or ca1:
                errors.append('Communication alarm: ca0 %d ca1 %d (the '
                              'request was received with a parity or '
                              'delimiter error)' % (ca0, ca1))
        names = DATA_FIELDS.get(ident, DATA_FIELDS[ABNORMAL_ANSWER_ID])
        fields = {}
        for name, (ss, es, v, _) in zip(names, msg[2:2 + len(names)]):
            fields[name] = v
            self.ann(ss, es, A_FIELD, ['%s: 0x%02x' % (name, v), name])
        for word in ('ABS', 'ABM'):
            if all(word + str(i) in fields for i in range(3)):
                v = sum(fields[word + str(i)] << (8 * i) for i in range(3))
                parts.append('%s %d' % (word, v))
        if 'ENID' in fields:
            parts.append('ENID %02x' % fields['ENID'])
        if 'ALMC' in fields:
            flags = [n for i, n in enumerate(ALMC)
                     if n and fields['ALMC'] >> i & 1]
            parts.append('ALMC %02x%s' % (fields['ALMC'], (' ' + ' '.join(
                flags)) if flags else ''))
        parts.append(self.crc(msg, errors, answer_length(ident)))
        return ', '.join(parts)
