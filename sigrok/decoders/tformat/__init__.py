##
## Part of this repository; MIT OR Apache-2.0, as the repository.
##

'''
Tamagawa T-format (Smart Abs TS5669 N127 specification), stacked on
sigrok's uart decoder (2.5 Mbit/s, 8 data bits LSB first, no parity, one
stop bit: "start bit 0, 8 data bits, delimiter 1").

A request is a control field (CF: sink code 010, Data ID cc0..cc3, ID
parity cc4), for EEPROM access followed by ADF, EDF and CRC (ID 6) or ADF
and CRC (ID D). The answer repeats the CF, then the status field (ea0,
ea1, ca0, ca1), the data fields of table 2 and a CRC, G(X) = X^8 + 1 over
every field but the CRC (the XOR of the bytes). Abnormal requests and
communication alarms are answered with Data ID 3's fields (table 5/6).

The line is half duplex: a request ends with its last field (its length
follows from its Data ID); what the line carries after it, if it starts
within the answer timeout, is the answer, up to a frame time of idle line
(the uart decoder's IDLE). Its length is held to what the request asks
for (an abnormal Data ID gets Data ID 3's 11 bytes).
'''

from .pd import Decoder
