#!/usr/bin/env python3
"""Writes the LMS fuzz seeds from the fact sheet's telegram layout and its known-answer
values (shared/protocols/sick-lms2xx.md). Run from this folder; the output is committed.
  seeds/stream/*    byte 0 = chunk length selector, then a device -> host byte stream
  seeds/telegram/*  CMD | DATA | STATUS of one reply telegram (the target adds the frame)"""
import os
import struct


def crc16(data):
    crc, prev = 0, 0
    for b in data:
        hi = prev
        prev = b
        crc = ((crc & 0x7FFF) << 1) ^ 0x8005 if crc & 0x8000 else (crc << 1)
        crc &= 0xFFFF
        crc ^= b | (hi << 8)
    return crc


def reply(body):  # body = CMD + DATA + STATUS
    frame = bytes([0x02, 0x80]) + struct.pack('<H', len(body)) + body
    return frame + struct.pack('<H', crc16(frame))


def scan_body(values, units_mm=True, partial=0, index=None, status=0x10):
    count = len(values) | (partial << 11) | ((1 if units_mm else 0) << 14)
    body = bytes([0xB0]) + struct.pack('<H', count) + b''.join(struct.pack('<H', v) for v in values)
    if index is not None:
        body += bytes([index & 0xFF])
    return body + bytes([status])


# Fact-sheet check: the known-answer request "start continuous output" ends in CRC 34 08.
assert crc16(bytes([0x02, 0x00, 0x02, 0x00, 0x20, 0x24])) == 0x0834

bodies = {
    'scan_mm_3': scan_body([1000, 8190 | 0x2000, 8191]),
    'scan_cm_361_index': scan_body([(i * 37) % 8200 for i in range(361)], units_mm=False, index=7),
    'scan_partial2_101': scan_body([500 + i for i in range(101)], partial=2),
    'mode_ok': bytes([0xA0, 0x00, 0x10]),
    'variant_accepted': bytes([0xBB, 0x01, 0xB4, 0x00, 0x32, 0x00, 0x10]),
    'config_34': bytes([0xF4]) + bytes(range(34)) + bytes([0x10]),
    'write_config_ok': bytes([0xF7, 0x01]) + bytes(33) + bytes([0x10]),
    'type_lms200': bytes([0xBA]) + b'LMS200;30106' + bytes([0x10]),
    'status_block': bytes([0xB1]) + b'V02.10 ' + bytes(100) + bytes([0x10]),
    'reset_reply': bytes([0x91, 0x10]),
}
os.makedirs('seeds/stream', exist_ok=True)
os.makedirs('seeds/telegram', exist_ok=True)
for name, body in bodies.items():
    with open(f'seeds/telegram/{name}', 'wb') as f:
        f.write(body)
# Streams: ACK then a reply; a scan split by garbage; two scans back to back.
streams = {
    'ack_mode_ok': bytes([7, 0x06]) + reply(bodies['mode_ok']),
    'garbage_scan': bytes([3]) + b'\x02\x80\xff\xff\x11' + reply(bodies['scan_mm_3']),
    'two_scans': bytes([63]) + reply(bodies['scan_cm_361_index']) + reply(bodies['scan_partial2_101']),
    'nak_type': bytes([1, 0x15, 0x06]) + reply(bodies['type_lms200']),
}
for name, data in streams.items():
    with open(f'seeds/stream/{name}', 'wb') as f:
        f.write(data)
