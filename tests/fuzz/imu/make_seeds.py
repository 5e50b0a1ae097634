#!/usr/bin/env python3
"""Writes the GX1 fuzz seeds from the fact sheet's reply layout (shared/protocols/
microstrain-3dm-gx1.md): echo, N big-endian words, checksum = (echo + sum of words) mod 2^16.
  seeds/reply/*   byte 0 = index into the protocol's commands (as fuzz_imu_reply.cpp orders
                  them), then the words
  seeds/stream/*  byte 0 = read size, byte 1 = parser setting, then a reply stream
Run from this folder."""
import os
import struct

# (command, words) with plausible values: level and still (1 g on Z), Euler 0x31, quaternion
# 0x0C (identity = 8192), temperature 0x07, firmware F0.
REPLY_WORDS = {0x01: 10, 0x02: 10, 0x03: 10, 0x04: 5, 0x05: 5, 0x06: 1, 0x07: 2, 0x0A: 10, 0x0B: 10,
               0x0C: 14, 0x0D: 4, 0x0E: 4, 0x0F: 1, 0x10: 2, 0x11: 1, 0x24: 1, 0x25: 4, 0x28: 2, 0x29: 2,
               0x31: 10, 0xF0: 1, 0xF1: 1}
EXAMPLES = {
    0x31: [0, 0, 0x4000, 0, 0, 0xFBE0, 0, 0, 0, 1234],
    0x0C: [8192, 0, 0, 0, 100, 0, 0xFF00, 0, 0, 0xFBE0, 0, 0, 0, 4321],
    0x0B: [8192, 0, 0, 0, 8192, 0, 0, 0, 8192, 7],
    0x07: [0x4000, 99],
    0xF0: [0x0302],
}


def reply(command, words):
    body = b''.join(struct.pack('>H', w & 0xFFFF) for w in words)
    return bytes([command]) + body + struct.pack('>H', (command + sum(words)) & 0xFFFF)


# The command list as the target builds it: every byte with a reply length, in byte order.
commands = sorted(REPLY_WORDS)
os.makedirs('seeds/reply', exist_ok=True)
os.makedirs('seeds/stream', exist_ok=True)
for command, words in EXAMPLES.items():
    assert len(words) == REPLY_WORDS[command]
    with open(f'seeds/reply/cmd_{command:02x}', 'wb') as f:
        f.write(bytes([commands.index(command)]) + b''.join(struct.pack('>H', w) for w in words))
stream = reply(0x31, EXAMPLES[0x31]) + reply(0x31, EXAMPLES[0x31][:9] + [1235]) + b'\x31\x00' + \
    reply(0x31, EXAMPLES[0x31][:9] + [1236])
with open('seeds/stream/euler_stream', 'wb') as f:
    f.write(bytes([7, 1]) + stream)
with open('seeds/stream/mixed_all', 'wb') as f:
    f.write(bytes([63, 0]) + reply(0xF0, EXAMPLES[0xF0]) + reply(0x0C, EXAMPLES[0x0C]) + reply(0x07, EXAMPLES[0x07]))
