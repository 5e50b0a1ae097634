#!/usr/bin/env python3
"""Writes seeds for fuzz_canopen_drive (12-byte records, see the target) from the CiA 301 /
402 frame layouts of shared/protocols/canopen-cia402.md: a drive (node 5) answering the
session's whole configuration by SDO, its heartbeat, then TPDO1 statuswords walking the
state machine to Operation Enabled, a set-point handshake, an EMCY and a fault. Run from
this folder."""
import os
import struct

NODE = 5


def record(cob, data, step_ms=1, flags=0):
    data = bytes(data)
    return bytes([step_ms | flags]) + struct.pack('>H', cob) + bytes([len(data)]) + data.ljust(8, b'\0')


def sdo_ack(index, sub):
    return record(0x580 + NODE, [0x60, index & 0xFF, index >> 8, sub, 0, 0, 0, 0])


def sdo_upload(index, sub, value, size):
    command = 0x43 | ((4 - size) << 2)  # expedited, size indicated
    return record(0x580 + NODE, [command, index & 0xFF, index >> 8, sub] + list(struct.pack('<I', value)))


def pdo_writes(comm, mapping, objects, event_timer):
    w = [(comm, 1), (comm, 2)] + ([(comm, 5)] if event_timer else []) + [(mapping, 0)]
    w += [(mapping, i + 1) for i in range(objects)] + [(mapping, 0), (comm, 1)]
    return w


def tpdo1(statusword, position):
    return record(0x180 + NODE, struct.pack('<Hi', statusword, position))


configuration = [sdo_upload(0x6502, 0, 0x1, 4)]
writes = [(0x1017, 0)] + pdo_writes(0x1800, 0x1A00, 2, True) + pdo_writes(0x1801, 0x1A01, 1, True) + \
    pdo_writes(0x1400, 0x1600, 2, False) + pdo_writes(0x1401, 0x1601, 1, False) + [(0x6060, 0), (0x6083, 0), (0x6084, 0)]
configuration += [sdo_ack(i, s) for i, s in writes]
configuration += [sdo_upload(0x6061, 0, 1, 1)]
heartbeat = record(0x700 + NODE, [0x05])
enable = [tpdo1(sw, 1000) for sw in (0x0250, 0x0231, 0x0233, 0x0237)]
setpoint = [record(0x180 + NODE, struct.pack('<Hi', 0x0237, 1000)[:6] + b'\0\0', flags=0x40)[:4] +
            struct.pack('<d', 0.2), tpdo1(0x1237, 1010), tpdo1(0x0637, 1100)]
fault = [record(0x80 + NODE, [0x10, 0x23, 0x01, 0, 0, 0, 0, 0]), tpdo1(0x0218, 1100), tpdo1(0x0250, 1100)]

os.makedirs('seeds', exist_ok=True)
for name, records in {
    'configure_enable': configuration + [heartbeat] + enable,
    'configure_enable_setpoint_fault': configuration + [heartbeat] + enable + setpoint + [heartbeat] + fault,
    'silent_drive': [record(0, [], step_ms=63)] * 20,
}.items():
    with open(f'seeds/{name}', 'wb') as f:
        f.write(b''.join(records))
