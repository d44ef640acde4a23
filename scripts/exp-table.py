#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Prints the 2^(k/128) table of geostat/exp_batch.cpp (glibc's exp, since 2.28, uses the same
definition): for k in [0, 128), H = 2^(k/128) rounded to double, T = 2^(k/128) / H - 1 rounded
to double; entry 2k is T's bits, entry 2k + 1 is H's bits minus k << 45. Computed with 60
decimal digits, so both roundings are exact."""
import struct
from decimal import Decimal, getcontext

getcontext().prec = 60


def bits(x):
    return struct.unpack("<Q", struct.pack("<d", x))[0]


words = []
for k in range(128):
    exact = Decimal(2) ** (Decimal(k) / Decimal(128))
    h = float(exact)  # float(Decimal) rounds correctly
    t = float(exact / Decimal(h) - 1)
    words += [bits(t), (bits(h) - (k << 45)) % 2**64]
for i in range(0, len(words), 4):
    print("    " + " ".join(f"0x{w:016x}," for w in words[i:i + 4]))
