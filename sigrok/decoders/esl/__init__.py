##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

'''
ESL (QS35-M40M-E12F "ESL Safety serial protocol"), stacked on sigrok's
uart decoder (10 Mbit/s, 8 data bits LSB first, no parity, one stop bit).

The host's request is a command frame (CF: encoder address EAD0..2, Data
ID CC0..3, odd parity CC4) and an 8-bit CRC; Data ID E adds ADF, Data ID
F ADF and EDF. The encoder repeats the CF, then the fields of table 12:
a status frame (CA0 CA1 EA0 EA1 DD0..DD3), the data frames and a CRC;
position reads with safety (Data ID 1, 2, 8, B) carry a CRC-16 and a
second channel (CF2, SF2, ALM2, the redundant single turn RS0/RS1 and the
sequence counter SC2) with its own CRC-16. ADF is Busy then Add0..Add6.

CRCs: over every field but the CRC, bits in wire order (LSB first);
CRC-8 x^8 + x^5 + x^3 + x^2 + x + 1, both channels preset 0x00; CRC-16
x^16 + x^14 + x^12 + x^11 + x^8 + x^5 + x^4 + x^2 + 1, CH1 preset 0x0000,
CH2 0xFFFF, an odd number of fields padded with a zero byte; both sent
LSB first. The seed's hex values 8'h97 and 16'hAC9A are these equations in
the notation that drops the +1 term (x^n down to x^1); the register here
shifts the wire's bits into its top and sends its output reflected.

Checks beyond the CRCs: the answer's CF against the request's, CF2
against CF, the channels' alarms and sequence counters (SC2 is SC1's low
7 bits), each address's SC1 one more than at its last safety read, the
status frame's communication alarms. A request to the broadcast address
is not answered.
'''

from .pd import Decoder
