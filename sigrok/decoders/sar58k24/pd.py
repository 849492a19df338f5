##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

import sigrokdecode as srd
from encoder_line import (Common, gray_to_binary, REQUEST_ANSWER_ANNOTATIONS,
                          REQUEST_ANSWER_ROWS, A_FIELD, A_REQUEST,
                          A_ANSWER, A_ERROR)

HEADER = 0xFF
TAG_FIXED = 0x81
BUS_PREFIX = (0xBC, 0xAA)
READ_BASE, ZERO_BASE = 0xB0, 0xC0


def data_bytes(bits):
    '''Bytes of position data for a resolution (the manual's tables).'''
    return 2 if bits <= 16 else 3 if bits <= 24 else 4



class Decoder(Common, srd.Decoder):
    api_version = 3
    id = 'sar58k24'
    name = 'SAR58K24'
    longname = 'SAR58K24 asynchronous serial'
    desc = 'SAR58K24 encoder position frames and bus commands.'
    license = 'mit'
    inputs = ['uart']
    outputs = []
    tags = ['Embedded/industrial']
    options = (
        {'id': 'bits', 'desc': 'Resolution in bits', 'default': 16},
        {'id': 'code', 'desc': 'Code', 'default': 'binary',
         'values': ('binary', 'gray')},
        {'id': 'timeout_ms', 'desc': 'Answer timeout after a bus command '
         '(ms)', 'default': 5.0},
    )
    annotations = REQUEST_ANSWER_ANNOTATIONS
    annotation_rows = REQUEST_ANSWER_ROWS

    def reset(self):
        self.samplerate = None
        self.message = []  # (ss, es, value, valid)
        self.parity_errors = []
        self.glitch = False
        self.pending = None  # (ss, es, address, zero) of a bus command
        self.deadline = None


    def frame_length(self):
        return 2 + data_bytes(self.options['bits']) + 1

    def decode(self, ss, es, data):
        ptype, rxtx, pdata = data
        if rxtx != 0:
            return
        if ptype == 'PARITY ERROR':
            self.parity_errors.append(ss)
            return
        if ptype == 'INVALID STARTBIT':
            # A low pulse shorter than half a bit: no character (the uart
            # decoder still passes a FRAME for it).
            self.glitch = True
            self.ann(ss, es, A_FIELD, ['Glitch (no start bit)', 'Glitch'])
            return
        if ptype == 'IDLE':
            if self.message:
                self.close()
            if self.deadline is not None and es > self.deadline:
                self.no_answer()
            return
        if ptype != 'FRAME':
            return
        if self.glitch:
            self.glitch = False
            return
        value, valid = pdata
        self.message.append((ss, es, value, valid))
        first = self.message[0][2]
        if first == BUS_PREFIX[0] and len(self.message) == 3:
            self.close()
        elif first == HEADER and len(self.message) == self.frame_length():
            self.close()

    def no_answer(self):
        ss, es = self.pending[0], self.pending[1]
        if not self.pending[3]:  # a zeroing command may go unanswered
            self.ann(ss, es, A_ERROR, ['Error: No answer within the timeout',
                                       'Error: no answer'])
        self.pending = None
        self.deadline = None

    def close(self):
        msg, self.message = self.message, []
        errors = []
        ss, es = msg[0][0], msg[-1][1]
        for i, (s, e, v, valid) in enumerate(msg):
            if not valid:
                errors.append('Byte %d (0x%02x): UART framing error' % (i, v))
            if any(s <= p < e for p in self.parity_errors):
                errors.append('Byte %d (0x%02x): parity error' % (i, v))
        self.parity_errors = [p for p in self.parity_errors if p >= es]
        data = ' '.join('%02x' % m[2] for m in msg)
        values = [m[2] for m in msg]
        if values[:2] == list(BUS_PREFIX) and len(values) == 3:
            self.command(msg, data, errors)
        elif values[0] == HEADER and len(values) == self.frame_length():
            restart = self.resync(values)
            if restart:
                # A bad checksum and a header later on: the bytes before it
                # were no frame (noise, or a frame cut short).
                self.message = msg[restart:]
                msg = msg[:restart]
                data = ' '.join('%02x' % m[2] for m in msg)
                errors.append('Not a frame of the manual: %s, then a header'
                              % data)
                self.ann(ss, msg[-1][1], A_ANSWER, ['Answer: bytes %s' % data,
                                                    'Bytes'])
                for e in errors:
                    self.ann(ss, msg[-1][1], A_ERROR, ['Error: ' + e, 'Error'])
                return
            self.position(msg, data, errors)
        else:
            errors.append('Not a frame of the manual: %d bytes starting 0x%02x'
                          % (len(values), values[0]))
            self.ann(ss, es, A_ANSWER, ['Answer: bytes %s' % data, 'Bytes'])
            self.pending = self.deadline = None
        for e in errors:
            self.ann(ss, es, A_ERROR, ['Error: ' + e, 'Error'])

    def resync(self, values):
        '''Where a frame may start again inside a message whose checksum
        fails (FF followed by 81 or Bx), or 0.'''
        if sum(values[:-1]) & 0xFF == values[-1]:
            return 0
        for i in range(1, len(values) - 1):
            if values[i] == HEADER and (values[i + 1] == TAG_FIXED or
                                        values[i + 1] & 0xF0 == READ_BASE):
                return i
        return 0

    def command(self, msg, data, errors):
        ss, es, code, _ = msg[2]
        zero = code & 0xF0 == ZERO_BASE
        if code & 0xF0 not in (READ_BASE, ZERO_BASE):
            errors.append('Bus command 0x%02x is neither Bx nor Cx' % code)
        address = code & 0x0F
        self.ann(ss, es, A_FIELD, ['%s encoder %d' % ('Zero' if zero else
                                                      'Read', address),
                                   'Cx' if zero else 'Bx'])
        self.ann(msg[0][0], es, A_REQUEST, ['Command: bytes %s; %s address %d'
                                            % (data, 'zero' if zero else 'read',
                                               address), 'Command'])
        self.pending = (msg[0][0], es, address, zero)
        timeout = self.options['timeout_ms'] * 1e-3
        self.deadline = es + int(timeout * (self.samplerate or 0))

    def position(self, msg, data, errors):
        values = [m[2] for m in msg]
        tag = values[1]
        self.ann(msg[1][0], msg[1][1], A_FIELD, ['Tag: 0x%02x' % tag, 'Tag'])
        if tag != TAG_FIXED and tag & 0xF0 != READ_BASE:
            errors.append('Not a frame of the manual: second byte 0x%02x is '
                          'neither 81 nor Bx' % tag)
        elif self.pending is not None:
            address = self.pending[2]
            if tag not in (TAG_FIXED, READ_BASE | address):
                errors.append('Answer tagged 0x%02x, the command asked '
                              'encoder %d' % (tag, address))
        elif tag != TAG_FIXED:
            errors.append('Frame tagged 0x%02x without a bus command' % tag)
        raw = 0
        for v in values[2:-1]:
            raw = (raw << 8) | v
        value = gray_to_binary(raw) if self.options['code'] == 'gray' else raw
        self.ann(msg[2][0], msg[-2][1], A_FIELD, ['Position: %d' % value,
                                                  '%d' % value])
        sent, want = values[-1], sum(values[:-1]) & 0xFF
        ok = sent == want
        self.ann(msg[-1][0], msg[-1][1], A_FIELD, [
            'Checksum: 0x%02x %s' % (sent, 'ok' if ok else
                                     'bad (sum 0x%02x)' % want), 'Sum'])
        if not ok:
            errors.append('Checksum error: sent 0x%02x, sum 0x%02x'
                          % (sent, want))
        self.ann(msg[0][0], msg[-1][1], A_ANSWER, [
            'Answer: bytes %s; position %d, checksum %s'
            % (data, value, 'ok' if ok else 'bad'), 'Position %d' % value])
        self.pending = None
        self.deadline = None
