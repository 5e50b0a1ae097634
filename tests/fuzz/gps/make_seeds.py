#!/usr/bin/env python3
"""Writes the seeds of fuzz_gps_frame (byte 0 = framing, then the frame's content without its
checksum, see fuzz_gps_frame.cpp) from frames of the real captures in shared/data/real, and a
few hand-written streams for fuzz_gps_stream (byte 0 = read size). Run from this folder."""
import os
import re

REAL = '../../../../shared/data/real'
os.makedirs('seeds/frame', exist_ok=True)
os.makedirs('seeds/stream', exist_ok=True)


def write(folder, name, data):
    with open(f'seeds/{folder}/{name}', 'wb') as f:
        f.write(data)


# Binary long-header frames: header + body without the CRC, framing 0.
binary = open(f'{REAL}/swri-novatel_gps_driver/bestpos-bestvel-psrdop2-sync.tcp-payload.bin', 'rb').read()
seen = set()
for m in re.finditer(rb'\xaa\x44\x12', binary):
    at = m.start()
    header = binary[at + 3]
    body = int.from_bytes(binary[at + 8:at + 10], 'little')
    msg_id = int.from_bytes(binary[at + 4:at + 6], 'little')
    if msg_id in seen or at + header + body > len(binary):
        continue
    seen.add(msg_id)
    write('frame', f'binary_id{msg_id}', bytes([0]) + binary[at:at + header + body])

# ASCII logs and NMEA sentences: the text between the start character and '*'.
text = open(f'{REAL}/swri-novatel_gps_driver/gpgga-gprmc-bestpos.udp-payload.bin', 'rb').read()
text += open(f'{REAL}/gpsd-test-daemon/nmea-rtk.log', 'rb').read()
text += open(f'{REAL}/gavlab-novatel/OneEach.ASC', 'rb').read()
names = set()
for m in re.finditer(rb'([#%$])([A-Z0-9]+)([^*\r\n]*)\*', text):
    start, name = m.group(1), m.group(2)
    if name in names:
        continue
    names.add(name)
    framing = {b'#': 2, b'%': 3, b'$': 4}[start]
    write('frame', f'text_{name.decode()}', bytes([framing]) + m.group(2) + m.group(3))

# Sentences the captures lack: GST (sigmas) and VTG (velocity).
write('frame', 'text_GPGST', b'\x04GPGST,172814.0,0.006,0.023,0.020,273.6,0.023,0.020,0.031')
write('frame', 'text_GPVTG', b'\x04GPVTG,054.7,T,034.4,M,005.5,N,010.2,K')

# Streams: a prompt, a reply, an empty no-fix GGA, then garbage before a real BESTPOSA line.
line = re.search(rb'#BESTPOSA[^\r\n]*\r\n', text).group(0)
write('stream', 'prompt_reply_nofix', bytes([5]) + b'[COM1]<OK\r\n$GPGGA,,,,,,0,,,,,,,,*66\r\n' + b'\xaa\x44\x12\x1c' + line)
write('stream', 'split_binary', bytes([1]) + binary[:600])
