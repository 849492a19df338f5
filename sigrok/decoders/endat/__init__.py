##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

'''
EnDat 2.1 / 2.2 (HEIDENHAIN D297403, "EnDat 2.2"), read at the subsequent
electronics' (the master's) pins: one clock line and the bidirectional
data line.

From the seed's text: the master sends each mode bit with the falling clock
edge and the encoder takes it with the rising edge; the first falling edge
latches the position; the mode bits follow from the second falling edge
(M2 M1 M0 and, for type 2.1, their complements: section 2.3.2.1). The
encoder answers with a start bit, F1, F2 (type 2.2 only, active low), the
position LSB first and a 5-bit CRC (appendix A4 MakeCrcPos); with type 2.2
commands the selected additional data follow, additional datum 2 before
additional datum 1, each 24 bits (WRN, RM, Busy, I4..I0, 16 data bits) and
a CRC (MakeCrcNorm). "Encoder send test values" sends 40 bits LSB first.

What the figures (missing from the seed's text) would fix, read here as:
the master's 8-bit MRS code or address, 16-bit parameter and 5-bit CRC
(MakeCrcNorm) follow the mode bits of a type 2.1 memory, reset, test or
communication command, and the encoder then acknowledges with a start
bit, address and data (24 bits, MSB first) and a CRC; with a type 2.2
command that carries a parameter, the master's 29 bits are the last 29
clocked after the encoder's data. The additional data an encoder sends
follow the "Selection of memory area or of additional data" commands the
capture shows (or the ad1/ad2 options).

Encoder bits are read from the start bit's edge on, one clock period
each, at the middle of the period: that is how a cable's delay (any
length) is read without an option. The start bit's delay after the rising
clock edge before it is shown (the seed's delay measurement, 2.1.2).
With a continuous clock ("Encoder send position values" only) every
further value is decoded.

Errors shown: F1 set, F2 cleared, CRC errors (position, additional data,
the master's block), no start bit, a data line not driven after the mode
bits, type II (address or parameter returned inverted, appendix A2),
type III (additional datum I = 15 or 31), type IV (NOP returned while
other data are selected), an unknown mode command.
'''

from .pd import Decoder
