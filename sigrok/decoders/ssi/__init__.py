##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

'''
SSI (synchronous serial interface) of absolute position encoders: the
clock idles high with the data line; the first falling clock edge stores
the position, the encoder sends it MSB first, each bit changing at a rising
edge and read at the next falling edge; after the last clock the data line
stays low for the monoflop time T_m, then returns high (SAR58K24 manual,
SSI section: "When no signal is transmitted, both the clock and data remain
at high levels. The current value begins storage at the first falling edge
of the clock signal, while data transmission starts at the rising edge of
the clock").

Options: the number of bits the reader clocks, binary or Gray code, a
double read (the value clocked twice and compared), a wire check (one more
clock whose bit must be 0), the reader's sampling delay after each falling
edge (long cables) and the monoflop time (a read that starts while the data
line is still low is flagged).
'''

from .pd import Decoder
