#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Two hostile rigs for the integrations' tests, made from a good one: its
# first 1,000 bytes (truncated.pmrig) and the whole file with its middle
# byte changed (corrupt.pmrig, a checksum mismatch). Each binding must
# refuse both with the native loader's message.
#   hostile_rigs.py RIG.pmrig OUT-DIR
import os
import sys

data = bytearray(open(sys.argv[1], 'rb').read())
open(os.path.join(sys.argv[2], 'truncated.pmrig'), 'wb').write(data[:1000])
data[len(data) // 2] ^= 0x5A
open(os.path.join(sys.argv[2], 'corrupt.pmrig'), 'wb').write(data)
