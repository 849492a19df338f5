##
## Helpers shared by the position-encoder decoders in this folder (ssi,
## biss_c, endat, ...). Not a decoder itself: libsigrokdecode skips a
## folder without a Decoder class, and the decoders import this one by name
## because the decoders folder is on Python's path.
##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

import bisect

import sigrokdecode as srd


class Line:
    '''The changes of a set of channels over one frame, as recorded by
    record(): a level of any channel at any sample of the frame, so that a
    decoder can sample data a delay after a clock edge (a long cable, a
    receiver's synchroniser) without waiting backwards.'''

    def __init__(self, start, levels):
        self.samples = [start]
        self.levels = [tuple(levels)]

    def add(self, sample, levels):
        levels = tuple(levels)
        if levels != self.levels[-1]:
            self.samples.append(sample)
            self.levels.append(levels)

    def at(self, sample, channel):
        i = bisect.bisect_right(self.samples, sample) - 1
        return self.levels[max(i, 0)][channel]

    def edges(self, channel, kind):
        '''Samples where channel rises (kind 'r') or falls ('f').'''
        out = []
        for i in range(1, len(self.samples)):
            a, b = self.levels[i - 1][channel], self.levels[i][channel]
            if a != b and (b == 1) == (kind == 'r'):
                out.append(self.samples[i])
        return out

    def next_change(self, channel, after):
        '''The first sample > after where channel changes, or None.'''
        i = bisect.bisect_right(self.samples, after)
        level = self.at(after, channel)
        for j in range(i, len(self.samples)):
            if self.levels[j][channel] != level:
                return self.samples[j]
        return None


def crc(bits, width, poly, init):
    '''A bit-serial CRC register, MSB first: for each bit, the feedback is
    the register's top bit XOR the input; shift left; XOR the polynomial
    (without its x^width term) when the feedback is 1. Every protocol gives
    its own width, polynomial and preset from its seed.'''
    mask = (1 << width) - 1
    reg = init & mask
    for b in bits:
        fb = ((reg >> (width - 1)) & 1) ^ (b & 1)
        reg = (reg << 1) & mask
        if fb:
            reg ^= poly & mask
    return reg


def msb_first(bits):
    v = 0
    for b in bits:
        v = (v << 1) | (b & 1)
    return v


def lsb_first(bits):
    v = 0
    for i, b in enumerate(bits):
        v |= (b & 1) << i
    return v


def gray_to_binary(g):
    b = g
    shift = g >> 1
    while shift:
        b ^= shift
        shift >>= 1
    return b


def bit_string(bits):
    return ''.join(str(b) for b in bits)


def samples_of(samplerate, seconds):
    '''A time in whole samples (at least 0); needs the sample rate.'''
    if not samplerate:
        raise ValueError('the sample rate is unknown: give the capture one '
                         '(sigrok-cli -I vcd:samplerate=... or :downsample=...)')
    return max(0, int(round(seconds * samplerate)))



def record_clocked(dec, pins, clk, idle, either=False, linger=None):
    '''Records one frame of a clock that idles high, from the falling edge
    the caller has just matched (at dec.samplenum, with pins the levels
    wait() returned) until the clock has stayed high (either=True: at
    either level) for idle(longest complete phase) samples; before the
    first complete phase there is no limit. With linger, the other lines
    are recorded on for linger(longest phase) samples after the clock's
    last edge (data that a long cable delivers after the last clock),
    unless the clock falls again first: that edge starts the next frame.
    Returns (Line, end, next): end is the sample of the clock's last edge
    (either=True) or last rising edge; next is None, or the levels at the
    falling edge that starts the next frame (at dec.samplenum). When the
    capture ends, dec.capture_ended is set, and end is None if the frame
    was cut.'''
    n = len(pins)
    line = Line(dec.samplenum, pins)
    longest = 0
    since = None  # the clock's last edge that starts a timed phase
    last = dec.samplenum
    ended = None  # the sample the frame was found to have ended
    while True:
        conds = [{i: 'e'} for i in range(n)]
        limit = None
        if ended is not None:
            limit = since + max(idle(longest), linger(longest))
        elif since is not None and longest > 0:
            limit = since + idle(longest)
        if limit is not None:
            if limit <= dec.samplenum:
                return line, since, None
            conds.append({'skip': limit - dec.samplenum})
        try:
            pins = dec.wait(conds)
        except Exception:
            # libsigrokdecode 0.5 ends a capture with an error from wait():
            # the frame is whole if its clock had come to rest.
            dec.capture_ended = True
            whole = ended is not None or (since is not None and longest > 0)
            return line, (since if whole else None), None
        if limit is not None and not any(dec.matched[:n]):
            if ended is None and linger is not None:
                ended = dec.samplenum
                continue
            return line, since, None
        was = line.levels[-1][clk]
        if ended is not None and pins[clk] != was:
            # The clock moves again after the idle time: the next frame.
            return line, since, pins
        line.add(dec.samplenum, pins)
        if pins[clk] == was:
            continue
        if either or was == 1:
            longest = max(longest, dec.samplenum - last)
        last = dec.samplenum
        since = dec.samplenum if (either or pins[clk] == 1) else None


def clocked_frames(dec, clk, record, partial):
    '''The frames of a clock that idles high, one (Line, end) at a time:
    record(pins) records one from its first falling edge (record_clocked
    with the protocol's limits); partial(ss, es, where) is told of a frame
    the capture cuts, where = 'starts' (the capture starts inside it) or
    'ends'.'''
    pins = dec.wait({'skip': 0})
    pending = None
    if pins[clk] == 0:
        line, end, pending = record(pins)
        partial(0, end if end is not None else dec.samplenum, 'starts')
    while not getattr(dec, 'capture_ended', False):
        if pending is None:
            try:
                pins = dec.wait({clk: 'f'})
            except Exception:
                return  # the end of the capture (libsigrokdecode 0.5)
        else:
            pins = pending
        line, end, pending = record(pins)
        if end is None:
            partial(line.samples[0], dec.samplenum, 'ends')
            return
        yield line, end


class HalfDuplex:
    '''Requests and answers on one half-duplex line, from the packets of
    sigrok's uart decoder (its RX channel) stacked below a decoder.

    A request ends with its last field: request_length(first byte) bytes.
    What the line carries after it, if it starts within the answer timeout,
    is the answer; it ends at answer_length(first byte, request) bytes when
    its first byte repeats the request's, else at a frame time of idle
    line (uart's IDLE: libsigrokdecode 0.5 tells a stacked decoder nothing
    at the end of a capture, so a whole answer is closed at once).
    Bytes back to back with a closed answer are more of it. A glitch (an
    invalid start bit) is no character. A byte after a request left
    unanswered that cannot begin a request is that request's late answer.

    The owner gets on_request(msg), on_answer(msg, request, late, more)
    and on_no_answer(request), msg being [(ss, es, value, valid)].'''

    def __init__(self, owner, request_length, answer_length, is_request,
                 expects_answer):
        self.owner = owner
        self.request_length = request_length
        self.answer_length = answer_length
        self.is_request = is_request
        self.expects_answer = expects_answer
        self.message = []
        self.expect = 'request'
        self.request = None
        self.deadline = None
        self.answer_end = None
        self.glitch = False
        self.unanswered = False
        self.late = False
        self.timeout = 0

    def packet(self, ss, es, data, timeout_samples):
        '''One uart packet; timeout_samples: the answer timeout.'''
        self.timeout = timeout_samples
        ptype, rxtx, pdata = data
        if rxtx != 0:
            return
        if ptype == 'IDLE':
            if self.message:
                self.close()
            if self.expect == 'answer' and self.deadline is not None \
                    and es > self.deadline:
                self.no_answer()
            return
        if ptype == 'INVALID STARTBIT':
            self.glitch = True
            return
        if ptype != 'FRAME':
            return
        if self.glitch:
            self.glitch = False
            return
        value, valid = pdata
        bit = (es - ss) / 10.0
        if self.expect == 'request' and self.answer_end is not None \
                and ss - self.answer_end < 2 * bit:
            self.answer_end = es
            self.owner.on_answer([(ss, es, value, valid)], self.request,
                                 False, True)
            return
        self.answer_end = None
        if self.expect == 'request' and not self.message and \
                self.unanswered and not self.is_request(value, valid):
            self.expect, self.late = 'answer', True
        self.unanswered = False
        if self.expect == 'answer' and not self.message \
                and self.deadline is not None and ss > self.deadline:
            if self.is_request(value, valid):
                self.no_answer()
            else:
                self.late = True
        self.message.append((ss, es, value, valid))
        first = self.message[0][2]
        if self.expect == 'request':
            if len(self.message) >= self.request_length(first):
                self.close()
        elif self.request and first == self.request[0][2] and \
                len(self.message) == self.answer_length(first, self.request):
            self.answer_end = es
            self.close()

    def no_answer(self):
        self.owner.on_no_answer(self.request)
        self.expect = 'request'
        self.deadline = None
        self.unanswered = True

    def close(self):
        msg, self.message = self.message, []
        if self.expect == 'request':
            self.request = msg
            self.owner.on_request(msg)
            if self.expects_answer(msg):
                self.expect = 'answer'
                self.deadline = msg[-1][1] + self.timeout
        else:
            self.owner.on_answer(msg, self.request, self.late, False)
            self.expect = 'request'
            self.deadline = None
            self.late = False


class Common:
    '''What every decoder here does alike: reset() at construction, the
    sample rate from metadata, one annotation output, and ann() that
    puts an annotation of at least one sample. Listed before
    sigrokdecode.Decoder in a decoder's bases.'''

    def __init__(self):
        self.reset()

    def metadata(self, key, value):
        if key == srd.SRD_CONF_SAMPLERATE:
            self.samplerate = value

    def start(self):
        self.out_ann = self.register(srd.OUTPUT_ANN)

    def ann(self, ss, es, cls, texts):
        ss, es = int(ss), int(es)
        self.put(ss, max(es, ss + 1), self.out_ann, [cls, texts])

    def partial(self, ss, es, where):
        '''A frame the capture cuts (clocked_frames' callback); the
        decoder's FRAME_ANNOTATION class.'''
        self.ann(ss, es, self.FRAME_ANNOTATION, [
            'Partial: the capture %s inside a frame' % where, 'Partial'])


# The annotations of the decoders stacked on uart: classes, then rows.
REQUEST_ANSWER_ANNOTATIONS = (
    ('field', 'Field'),
    ('request', 'Request'),
    ('answer', 'Answer'),
    ('error', 'Error'),
)
A_FIELD, A_REQUEST, A_ANSWER, A_ERROR = range(4)
REQUEST_ANSWER_ROWS = (
    ('fields', 'Fields', (A_FIELD,)),
    ('frames', 'Frames', (A_REQUEST, A_ANSWER)),
    ('errors', 'Errors', (A_ERROR,)),
)
