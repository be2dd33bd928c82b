#!/usr/bin/env python3
"""tcp_receiver_restarts.py LOGS PORT_FILE: a receiver's TCP port that reboots. Listens on a
free port of 127.0.0.1 (written to PORT_FILE), sends each line of LOGS 50 ms apart to the first
client, closes the client and the port, listens again on the same port 0.5 s later and sends the
same lines to the next client (waiting up to 10 s for it), then closes."""
import socket
import sys
import time


def serve(port, lines, port_file=None):
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as server:
        server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        server.bind(("127.0.0.1", port))
        server.listen(1)
        if port_file:
            with open(port_file + ".tmp", "w") as f:
                f.write(str(server.getsockname()[1]))
            import os
            os.replace(port_file + ".tmp", port_file)
        server.settimeout(10)
        client, _ = server.accept()
        with client:
            for line in lines:
                client.sendall(line)
                time.sleep(0.05)
        return server.getsockname()[1]


def main():
    lines = open(sys.argv[1], "rb").read().splitlines(keepends=True)
    port = serve(0, lines, sys.argv[2])
    time.sleep(0.5)
    serve(port, lines)


main()
