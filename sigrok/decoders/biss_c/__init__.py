##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

'''
BiSS-C of absolute position encoders (SAR58K24 manual, BiSS-C section):
"The first rising edge of MA+ is used to latch the sensor state. The second
rising edge of MA+ triggers the encoder to pull SLO+ low" (the
acknowledge); then the start bit 1, the CDS bit, the position MSB first,
the error bit nE and the warning bit nW (both active low) and a 6-bit CRC
over data, nE and nW, g(x) = x^6 + x + 1, sent inverted. In a chain every
slave's section (CDS, data, nE, nW, CRC) follows the previous one. After
the last clock the slave holds SLO low for its timeout; the master sends
one control bit CDM per frame as the MA level during that timeout (MA low
= CDM 1).

The decoder measures the line delay at the master's pins from the
acknowledge (the SLO falling edge after the second rising MA edge) and
samples each bit at the middle of its clock period after that delay, so
long cables need no option.

Register access: the CDM and CDS bits of successive frames form control
frames (after at least 14 CDM zeros: S, CTS, ID, address, CRC-4, R, W, S,
8 data bits, CRC-4, P); a register read's data and CRC come back on the
CDS bit of the addressed slave, each one frame after the CDM bit it
answers. The address CRC covers CTS, ID and address. A command frame
(CTS = 0) carries 8 ID-select bits, a 2-bit command and a CRC-4 over CTS,
IDS and command.

Options: per-slave data widths and CRC widths and polynomials, separated by
/ (sigrok-cli takes commas between decoders), first slave (nearest the master's SLO input) first.
'''

from .pd import Decoder
