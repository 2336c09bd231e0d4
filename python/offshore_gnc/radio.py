"""The simulated radio link between the two vehicles' relays (simulation only, like the job's acoustic channel):
every byte the relays exchange crosses it, their TCP stream and their UDP datagrams, and meets what a radio does
to it: a one-way delay with jitter, a rate that queues what comes faster, and losses in bursts (fades); it delivers
in order. A lost datagram is gone; a lost TCP segment comes `retransmit` later, and what follows it waits (TCP
delivers in order).
The figures are sim::RadioParams (`radio_params` prints them, from config/relay/radio.yaml over the defaults: a
2.4 GHz WiFi link over water, docs/relay.md "The simulated radio"), in simulated time: the radio divides delays
by the job's speed-up and multiplies the rate by it. `down()` is the link fault: every connection is dropped, new
ones are refused and datagrams lost until `up()`; the relays then see what they would at sea.

How the relays are put behind it: the radio owns a loopback address of its own (127.0.0.2). The AUV's relay dials
the radio there instead of the USV's relay, and the radio dials the USV's relay from that address. Each relay
sends its datagrams to the address its TCP link comes from, at the UDP port its peer's hello announced (a
listening relay's is its TCP port): so the AUV's go to the radio at the USV relay's port, and the USV's to the
radio at the AUV relay's, which therefore listens on a port the job chose (`auv_udp_port`). The radio sends each
datagram on from its other face, so every source is the one the receiving relay expects."""
import heapq
import itertools
import json
import random
import select
import socket
import subprocess
import threading
import time

RADIO_HOST = "127.0.0.2"  # the radio's own loopback address (the relays are on 127.0.0.1)
MSS = 1448                # a TCP segment's payload: a lost one is retransmitted, not the whole read
TCP_OVERHEAD, UDP_OVERHEAD = 52, 28  # IP + TCP (with timestamps) / IP + UDP headers on the channel [bytes]


def load_params(path=None):
    """sim::RadioParams as the C++ table reads them (FILE's keys over the defaults, ranges checked): a dict."""
    from offshore_gnc import tools
    r = subprocess.run([tools.path("radio_params")] + ([path] if path else []), stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True, timeout=30)
    if r.returncode != 0:
        raise ValueError("radio parameters: " + r.stderr.strip())
    return json.loads(r.stdout)


class Channel:
    """One direction of the radio: its queue, delay and losses (Gilbert-Elliott: a bad state entered with the
    probability that gives the mean loss, left after loss_burst packets on average). Times in wall seconds."""

    def __init__(self, params, speedup, rng):
        self.p, self.rng = params, rng
        self.scale = 1.0 / speedup if speedup > 0 else 0.0  # simulated -> wall seconds (0: as fast as possible)
        loss, burst = params["loss"], params["loss_burst"]
        self.p_bad = loss / (burst * (1.0 - loss)) if loss > 0 else 0.0
        self.p_good = 1.0 / burst
        self.bad = False
        self.busy_until = self.last = self.last_tcp = 0.0
        self.stats = {"packets": 0, "lost": 0, "retransmitted": 0, "dropped_queue": 0}

    def _lost(self):
        self.bad = self.rng.random() >= self.p_good if self.bad else self.rng.random() < self.p_bad
        return self.bad

    def schedule(self, now, nbytes, tcp):
        """When a packet handed over now arrives, or None when it is lost (datagrams only)."""
        self.stats["packets"] += 1
        bits = 8.0 * (nbytes + (TCP_OVERHEAD if tcp else UDP_OVERHEAD))
        start = max(now, self.busy_until)
        if not tcp and start - now > self.p["queue"] * self.scale:
            self.stats["dropped_queue"] += 1  # the channel is full: what arrives now is lost
            return None
        self.busy_until = start + bits / self.p["bandwidth"] * self.scale
        jitter = self.rng.expovariate(1.0 / self.p["jitter"]) if self.p["jitter"] > 0 else 0.0
        # the link delivers in order (WiFi's link layer: its retries hold back what follows): the jitter delays but
        # never reorders (it did, the simulators publishing in bursts of wall time: a fifth of /usv_gps came late)
        due = max(self.busy_until + (self.p["latency"] + jitter) * self.scale, self.last)
        self.last = due
        if self._lost():
            if not tcp:
                self.stats["lost"] += 1
                return None
            self.stats["retransmitted"] += 1
            due += self.p["retransmit"] * self.scale
        if tcp:  # in order: a segment never overtakes the one before it
            due = max(due, self.last_tcp)
            self.last_tcp = due
        return due


class Radio:
    """target_port: the USV relay's TCP (and UDP) port on 127.0.0.1; the AUV's relay dials (RADIO_HOST,
    target_port) and listens (for its UDP) on 127.0.0.1:auv_udp_port. speedup: simulated seconds per wall second."""

    def __init__(self, target_port, auv_udp_port, params, speedup, seed=1):
        self.target = ("127.0.0.1", target_port)
        self.auv_udp = ("127.0.0.1", auv_udp_port)
        self.addr = (RADIO_HOST, target_port)
        rng = random.Random(seed)
        self.to_usv = Channel(params, speedup, random.Random(rng.random()))
        self.to_auv = Channel(params, speedup, random.Random(rng.random()))
        self.lock = threading.Lock()
        self.pairs = []  # [client (AUV side), server (USV side)]
        self.pending = []  # heap: (due, n, kind, destination, data)
        self.count = itertools.count()
        self.listener = None
        # the AUV-side face receives the AUV's datagrams (sent to the USV relay's port at the radio's address),
        # the USV-side face the USV's (sent to the AUV relay's port at the radio's address)
        self.udp_auv_side = self._udp((RADIO_HOST, target_port))
        self.udp_usv_side = self._udp((RADIO_HOST, auv_udp_port))
        self.running = True
        self.is_up = False
        self.forwarded = self.dropped_connections = self.udp_refused = 0
        self.up()
        self.thread = threading.Thread(target=self._serve, name="radio", daemon=True)
        self.thread.start()

    @staticmethod
    def _udp(addr):
        s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        s.bind(addr)
        s.setblocking(False)
        return s

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
            self.pending = []  # what was on the air is lost

    def close(self):
        self.down()
        self.running = False
        self.thread.join(2.0)
        self.udp_auv_side.close()
        self.udp_usv_side.close()

    def _send_later(self, channel, kind, destination, data, tcp):
        now = time.monotonic()
        for i in range(0, len(data), MSS if tcp else len(data) or 1):
            piece = data[i:i + MSS] if tcp else data
            due = channel.schedule(now, len(piece), tcp)
            if due is not None:
                heapq.heappush(self.pending, (due, next(self.count), kind, destination, piece))

    def _serve(self):
        while self.running:
            with self.lock:
                socks = ([self.listener] if self.listener else []) + [s for p in self.pairs for s in p]
                wait = min(0.05, max(0.0, self.pending[0][0] - time.monotonic())) if self.pending else 0.05
            try:
                readable = select.select(socks + [self.udp_auv_side, self.udp_usv_side], [], [], wait)[0]
            except (OSError, ValueError):  # a socket closed by down() meanwhile
                continue
            with self.lock:
                for s in readable:
                    if s is self.listener:
                        self._accept()
                    elif s is self.udp_auv_side or s is self.udp_usv_side:
                        self._datagram(s)
                    else:
                        self._stream(s)
                self._deliver()

    def _stream(self, s):
        pair = next((p for p in self.pairs if s in p), None)
        if pair is None:
            return
        try:
            data = s.recv(65536)
        except OSError:
            data = b""
        if data:
            to_usv = s is pair[0]
            self._send_later(self.to_usv if to_usv else self.to_auv, "tcp", pair[1] if to_usv else pair[0], data, True)
            return
        for x in pair:  # one side closed: close the other, as a cable would
            x.close()
        self.pairs.remove(pair)

    def _datagram(self, s):
        try:
            data, source = s.recvfrom(65536)
        except OSError:
            return
        # from the AUV's relay towards the USV's, or back; anything else (or while the radio is down) is not sent
        if s is self.udp_auv_side and source == self.auv_udp and self.is_up:
            self._send_later(self.to_usv, "udp", (self.udp_usv_side, self.target), data, False)
        elif s is self.udp_usv_side and source == self.target and self.is_up:
            self._send_later(self.to_auv, "udp", (self.udp_auv_side, self.auv_udp), data, False)
        else:
            self.udp_refused += 1

    def _deliver(self):
        now = time.monotonic()
        while self.pending and self.pending[0][0] <= now:
            _, _, kind, destination, data = heapq.heappop(self.pending)
            try:
                if kind == "tcp":
                    if any(destination in p for p in self.pairs):
                        destination.sendall(data)
                        self.forwarded += len(data)
                else:
                    destination[0].sendto(data, destination[1])
                    self.forwarded += len(data)
            except OSError:
                pass

    def _accept(self):
        try:
            client, _ = self.listener.accept()
        except OSError:
            return
        try:
            server = socket.create_connection(self.target, timeout=2.0, source_address=(RADIO_HOST, 0))
        except OSError:
            client.close()  # the USV's relay is not listening (yet): the dialler retries
            return
        server.settimeout(None)
        for s in (client, server):
            s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.pairs.append([client, server])

    def stats(self):
        """What crossed the radio, for the report."""
        with self.lock:
            return {"bytes_forwarded": self.forwarded, "connections_dropped": self.dropped_connections,
                    "to_usv": dict(self.to_usv.stats), "to_auv": dict(self.to_auv.stats)}

    def summary(self):
        s = self.stats()
        return "%d bytes forwarded, %d connections dropped by outages; to the USV %s, to the AUV %s" % (
            s["bytes_forwarded"], s["connections_dropped"],
            ", ".join("%s %d" % kv for kv in s["to_usv"].items()), ", ".join("%s %d" % kv for kv in s["to_auv"].items()))
