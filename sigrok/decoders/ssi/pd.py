##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

import sigrokdecode as srd
from encoder_line import (Common, record_clocked, clocked_frames, msb_first, gray_to_binary,
                          bit_string, samples_of)

CLK, DATA = 0, 1

# Annotation classes, in the order of `annotations` below.
A_BIT, A_LATCH, A_POSITION, A_COPY, A_WIRE, A_FRAME, A_ERROR = range(7)


class Decoder(Common, srd.Decoder):
    api_version = 3
    id = 'ssi'
    name = 'SSI'
    longname = 'SSI absolute encoder'
    desc = 'Synchronous serial interface of absolute position encoders.'
    license = 'mit'
    inputs = ['logic']
    outputs = []
    tags = ['Embedded/industrial']
    channels = (
        {'id': 'clk', 'name': 'CLK', 'desc': 'Clock (at the reader)'},
        {'id': 'data', 'name': 'DATA', 'desc': 'Data (at the reader)'},
    )
    options = (
        {'id': 'bits', 'desc': 'Bits per value (clocks the reader sends)',
         'default': 12},
        {'id': 'code', 'desc': 'Code', 'default': 'binary',
         'values': ('binary', 'gray')},
        {'id': 'double_read', 'desc': 'Double read (value clocked twice)',
         'default': 'no', 'values': ('no', 'yes')},
        {'id': 'wire_check', 'desc': 'Wire check (one more clock, bit 0)',
         'default': 'no', 'values': ('no', 'yes')},
        {'id': 'sample_delay_ns', 'desc': 'Sampling delay after each '
         'falling edge (ns)', 'default': 0},
        {'id': 'monoflop_us', 'desc': 'Monoflop time T_m (us)',
         'default': 500},
    )
    FRAME_ANNOTATION = A_FRAME
    annotations = (
        ('bit', 'Bit'),
        ('latch', 'Latch'),
        ('position', 'Position'),
        ('copy', 'Second copy'),
        ('wire', 'Wire check bit'),
        ('frame', 'Read'),
        ('error', 'Error'),
    )
    annotation_rows = (
        ('bits', 'Bits', (A_BIT, A_LATCH)),
        ('fields', 'Fields', (A_POSITION, A_COPY, A_WIRE)),
        ('frames', 'Reads', (A_FRAME,)),
        ('errors', 'Errors', (A_ERROR,)),
    )

    def reset(self):
        self.samplerate = None
        self.last_end = None


    def decode(self):
        bits = self.options['bits']
        gray = self.options['code'] == 'gray'
        double = self.options['double_read'] == 'yes'
        wire = self.options['wire_check'] == 'yes'
        if bits < 1:
            raise ValueError('ssi: option bits must be at least 1')
        delay = samples_of(self.samplerate,
                           self.options['sample_delay_ns'] * 1e-9)
        t_m = samples_of(self.samplerate, self.options['monoflop_us'] * 1e-6)
        self.last_end = None
        record = lambda pins: record_clocked(  # noqa: E731
            self, pins, CLK, lambda h: 2 * h + 2)
        for line, end in clocked_frames(self, CLK, record, self.partial):
            self.frame((line, end), bits, gray, double, wire, delay, t_m)

    def frame(self, recorded, bits, gray, double, wire, delay, t_m):
        line, end = recorded
        start = line.samples[0]
        falls = line.edges(CLK, 'f')
        self.ann(start, falls[0] if falls else end, A_LATCH, ['Latch', 'L'])
        errors = []
        if line.at(start, DATA) == 0:
            errors.append(('Line not idle: data low at the first falling '
                           'edge (monoflop running or line stuck low)',
                           'line_not_idle'))
        if self.last_end is not None and start - self.last_end < t_m:
            errors.append(('Monoflop violation: read started %d samples '
                           'after the last, T_m is %d' %
                           (start - self.last_end, t_m), 'monoflop'))
        self.last_end = end
        # Bit k is read at falling edge k+1 (the first one stores the value),
        # plus the reader's sampling delay; it spans from the rising edge
        # that launched it to the next one.
        rises = line.edges(CLK, 'r')
        got = []
        for k, f in enumerate(falls):
            launch = rises[k] if k < len(rises) else f
            got.append(line.at(f + delay, DATA))
            nxt = rises[k + 1] if k + 1 < len(rises) else f + 1
            self.ann(launch, nxt, A_BIT, ['%d' % got[-1]])
        spans = [(rises[k], rises[k + 1] if k + 1 < len(rises) else falls[k])
                 for k in range(len(got))]
        want = bits * (2 if double else 1) + (1 if wire else 0)
        if len(got) != want:
            errors.append(('Clock count: %d bits clocked, the options say %d'
                           % (len(got), want), 'clock_count'))
        value = None
        if len(got) >= bits:
            raw = msb_first(got[:bits])
            value = gray_to_binary(raw) if gray else raw
            self.ann(spans[0][0], spans[bits - 1][1], A_POSITION,
                     ['Position: %d' % value, 'Pos: %d' % value, '%d' % value])
        rest = bits
        if double and len(got) >= 2 * bits:
            raw2 = msb_first(got[bits:2 * bits])
            copy = gray_to_binary(raw2) if gray else raw2
            self.ann(spans[bits][0], spans[2 * bits - 1][1], A_COPY,
                     ['Second copy: %d' % copy, 'Copy: %d' % copy])
            if copy != value:
                errors.append(('Double read mismatch: %d then %d'
                               % (value, copy), 'double_read_mismatch'))
            rest = 2 * bits
        if wire and len(got) > rest:
            self.ann(spans[rest][0], spans[rest][1], A_WIRE,
                     ['Wire check: %d' % got[rest], 'W: %d' % got[rest]])
            if got[rest] != 0:
                errors.append(('Wire check failed: bit after the value is 1',
                               'wire_check_failed'))
        text = 'Read: position %s, bits %s' % (
            value if value is not None else '?', bit_string(got))
        self.ann(start, end, A_FRAME, [text, 'Pos %s' % value])
        for long_text, short in errors:
            self.ann(start, end, A_ERROR, ['Error: ' + long_text,
                                           'Error: ' + short])
