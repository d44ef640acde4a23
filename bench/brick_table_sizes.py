# SPDX-License-Identifier: BSD-3-Clause
# Sizes of the GL renderer's derived brick tables for a .vxl (render/brick_lookup.h): the
# brick index and dual boxes over the occupied bricks' box (now) and over the whole grid (before
# issue 30), and the per-occupied-brick entries. Reads the header and BOCC (docs/format.md).
# Usage: python3 bench/brick_table_sizes.py FILE.vxl
import struct, sys
b = open(sys.argv[1], 'rb').read()
table_off, count = struct.unpack_from('<QI', b, 24)
grid = struct.unpack_from('<3I', b, 52)
K = struct.unpack_from('<Q', b, 176)[0]
for i in range(count):
    sid, eb, off, size = struct.unpack_from('<IIQQ', b, table_off + 32 * i)
    if sid == int.from_bytes(b'BOCC', 'little'):
        words = struct.unpack_from('<%dI' % (size // 4), b, off)
lo = [1 << 30] * 3; hi = [-1] * 3
for w, word in enumerate(words):
    while word:
        bit = (word & -word).bit_length() - 1; word &= word - 1
        n = w * 32 + bit
        c = (n % grid[0], n // grid[0] % grid[1], n // (grid[0] * grid[1]))
        lo = [min(a, x) for a, x in zip(lo, c)]; hi = [max(a, x) for a, x in zip(hi, c)]
box = [h - l + 1 for l, h in zip(lo, hi)] if K else [0, 0, 0]
G = grid[0] * grid[1] * grid[2]; B = box[0] * box[1] * box[2]
D = (box[0] + 1) * (box[1] + 1) * (box[2] + 1) if K else 0
Dg = (grid[0] + 1) * (grid[1] + 1) * (grid[2] + 1)
print(f"{sys.argv[1]}: grid {grid}, occupied box {box} from {lo}, K {K}")
print(f"  brick index: grid-wide {4*G/1024:.1f} KiB, box {4*B/1024:.1f} KiB")
print(f"  dual boxes: grid-wide {4*Dg/1024:.1f} KiB, box {4*D/1024:.1f} KiB; entries {8*K/1024:.1f} KiB")
