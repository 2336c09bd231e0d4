"""The simulated radio link between the two vehicles' relays (simulation only, the main job's like its acoustic
channel): the AUV's relay dials this forwarder instead of the USV's relay, and it passes the bytes both ways
unchanged (the relay's own authentication and framing run end to end). `down()` is a radio outage: every
connection is dropped and new ones are refused until `up()`. The relays then see what they would at sea: frames
stop, the link times out, reconnections fail with backoff until the radio is back."""
import select
import socket
import threading


class Radio:
    def __init__(self, target_port, listen_port, host="127.0.0.1"):
        self.target = (host, target_port)
        self.addr = (host, listen_port)
        self.lock = threading.Lock()
        self.pairs = []  # [client, server] sockets
        self.listener = None
        self.running = True
        self.is_up = False
        self.forwarded = self.dropped_connections = 0
        self.up()
        self.thread = threading.Thread(target=self._serve, name="radio", daemon=True)
        self.thread.start()

    def up(self):
        with self.lock:
            if self.is_up:
                return
            s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
            s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            s.bind(self.addr)
            s.listen(4)
            self.listener, self.is_up = s, True

    def down(self):
        with self.lock:
            if not self.is_up:
                return
            self.is_up = False
            self.listener.close()
            self.listener = None
            for pair in self.pairs:
                for s in pair:
                    s.close()
            self.dropped_connections += len(self.pairs)
            self.pairs = []

    def close(self):
        self.down()
        self.running = False
        self.thread.join(2.0)

    def _serve(self):
        while self.running:
            with self.lock:
                socks = ([self.listener] if self.listener else []) + [s for p in self.pairs for s in p]
            if not socks:
                select.select([], [], [], 0.05)
                continue
            try:
                readable = select.select(socks, [], [], 0.05)[0]
            except (OSError, ValueError):  # a socket closed by down() meanwhile
                continue
            with self.lock:
                for s in readable:
                    if s is self.listener:
                        self._accept()
                        continue
                    pair = next((p for p in self.pairs if s in p), None)
                    if pair is None:
                        continue
                    other = pair[1] if s is pair[0] else pair[0]
                    try:
                        data = s.recv(65536)
                        if data:
                            other.sendall(data)
                            self.forwarded += len(data)
                            continue
                    except OSError:
                        pass
                    for x in pair:  # one side closed: close the other, as a cable would
                        x.close()
                    self.pairs.remove(pair)

    def _accept(self):
        try:
            client, _ = self.listener.accept()
        except OSError:
            return
        try:
            server = socket.create_connection(self.target, timeout=2.0)
        except OSError:
            client.close()  # the USV's relay is not listening (yet): the dialler retries
            return
        server.settimeout(None)
        self.pairs.append([client, server])

    def summary(self):
        return "%d bytes forwarded, %d connections dropped by outages" % (self.forwarded, self.dropped_connections)
