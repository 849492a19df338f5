##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

'''
SAR58K24 asynchronous serial modes (Changchun Rongde Optics SAR58K24
manual, 3.1 to 3.3), stacked on sigrok's uart decoder (8 data bits LSB
first, one stop bit; parity "can be added according to customer
requirements": give it to uart).

Position frames: FF 81, the position high byte first (2 bytes up to 16
bits, 3 up to 24, 4 above), and a checksum, "the sum of the first n bytes
of data with the lower 8 bits". Timed send and pulse handshake send them
unasked; in bus mode the host sends BC AA Bx (read encoder x) or BC AA Cx
(zero encoder x), and "the second byte of the return data is the product
address number" (FF Bx); every frame table shows FF 81, which is accepted
as well. A position is shown in binary or, with code=gray, decoded from
Gray.
'''

from .pd import Decoder
