"""The simulated radio between the relays (python/offshore_gnc/radio.py, sim::RadioParams): its channel's statistics
(losses and their bursts, delay, rate), and the sockets as the relays meet them: TCP in order and complete through
losses, datagrams each way from the source the receiving relay accepts, nothing while the link is down."""
import random
import socket
import statistics
import time

import pytest

from offshore_gnc import radio as radio_link
from offshore_gnc.testing.masters import free_port

DEFAULTS = {"latency": 0.01, "jitter": 0.005, "loss": 0.02, "loss_burst": 3.0, "bandwidth": 2e6, "retransmit": 0.2,
            "queue": 0.5}


def test_the_shipped_parameters_are_the_tables_defaults_and_validated(tmp_path):
    assert radio_link.load_params() == DEFAULTS
    assert radio_link.load_params(radio_link.__file__.replace("python/offshore_gnc/radio.py", "config/relay/radio.yaml")) \
        == DEFAULTS
    bad = tmp_path / "bad.yaml"
    bad.write_text("loss: 2\n")
    with pytest.raises(ValueError, match="loss"):
        radio_link.load_params(str(bad))


def test_losses_come_in_bursts_at_the_mean_rate():
    ch = radio_link.Channel(DEFAULTS, 1.0, random.Random(4))
    lost, runs, run = [], [], 0
    t = 0.0
    for _ in range(200000):
        t += 0.01  # a datagram every 10 ms: the channel never queues
        got = ch.schedule(t, 100, tcp=False) is None
        lost.append(got)
        if got:
            run += 1
        elif run:
            runs.append(run)
            run = 0
    assert abs(sum(lost) / len(lost) - 0.02) < 0.003
    assert abs(statistics.mean(runs) - 3.0) < 0.3  # Gilbert-Elliott: geometric runs of mean loss_burst


def test_delay_rate_and_order():
    p = dict(DEFAULTS, loss=0.0)
    ch = radio_link.Channel(p, 1.0, random.Random(1))
    delays = [ch.schedule(10.0 * i, 100, tcp=False) - 10.0 * i for i in range(5000)]
    # one packet alone: its time on the air (128 bytes at 2 Mbit/s) + latency + exponential jitter
    assert abs(statistics.mean(delays) - (128 * 8 / 2e6 + 0.01 + 0.005)) < 0.0005
    assert min(delays) >= 128 * 8 / 2e6 + 0.01
    # datagrams handed over together (a simulator publishing a burst of steps) arrive in the order they were sent
    burst = [ch.schedule(1e6, 100, tcp=False) for _ in range(200)]
    assert burst == sorted(burst)
    # a burst of 1000 segments queues at the channel's rate and arrives in order
    ch = radio_link.Channel(dict(DEFAULTS, loss=0.1), 1.0, random.Random(2))
    due = [ch.schedule(0.0, 1448, tcp=True) for _ in range(1000)]
    assert all(d is not None for d in due) and due == sorted(due)  # TCP: late (retransmitted), never lost
    assert abs(due[-1] - 1000 * 1500 * 8 / 2e6) < 0.2 + 0.05   # the rate, plus a retransmission at most
    assert ch.stats["retransmitted"] > 50
    # at 20 times real time everything is 20 times quicker in wall time
    fast = radio_link.Channel(p, 20.0, random.Random(1))
    assert abs(fast.schedule(0.0, 100, tcp=False) * 20.0 - delays[0]) < 1e-9
    # datagrams that would wait longer than `queue` for the channel are dropped
    slow = radio_link.Channel(dict(p, bandwidth=1e4), 1.0, random.Random(1))
    sent = [slow.schedule(0.0, 1000, tcp=False) for _ in range(20)]
    assert sent.count(None) > 10 and slow.stats["dropped_queue"] == sent.count(None)


class FakeRelays:
    """The two relays' sockets as the job sets them up: the USV's listening (TCP and UDP on one port), the AUV's
    UDP on its own listening port, dialling the radio."""

    def __init__(self):
        self.usv_port, self.auv_port = free_port(), free_port()
        self.usv_tcp = socket.socket()
        self.usv_tcp.bind(("127.0.0.1", self.usv_port))
        self.usv_tcp.listen(1)
        self.usv_udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.usv_udp.bind(("127.0.0.1", self.usv_port))
        self.auv_udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.auv_udp.bind(("127.0.0.1", self.auv_port))
        for s in (self.usv_udp, self.auv_udp):
            s.settimeout(0.05)

    def connect(self):
        auv = socket.create_connection((radio_link.RADIO_HOST, self.usv_port), timeout=2.0)
        usv, peer = self.usv_tcp.accept()
        usv.settimeout(2.0)
        return auv, usv, peer

    def close(self):
        for s in (self.usv_tcp, self.usv_udp, self.auv_udp):
            s.close()


def closed(s):
    try:
        return s.recv(1) == b""
    except OSError:
        return True


def test_the_relays_traffic_crosses_it_both_ways():
    relays = FakeRelays()
    radio = radio_link.Radio(relays.usv_port, relays.auv_port, dict(DEFAULTS, loss=0.05), 20.0, seed=3)
    try:
        auv, usv, peer = relays.connect()
        assert peer[0] == radio_link.RADIO_HOST  # the USV's relay sees the radio: its datagrams go there
        # TCP: 300 kB each way, complete and in order despite the losses
        blob = bytes(random.Random(5).getrandbits(8) for _ in range(300000))
        auv.sendall(blob)
        got = b""
        while len(got) < len(blob):
            got += usv.recv(65536)
        assert got == blob
        # datagrams: from the AUV relay's port to the USV relay's at the radio's address, and back, in batches
        # drained before the next (a burst of 400 overflows the sockets' kernel buffers on a loaded machine: a
        # loss that is the test's, not the radio's)
        received = {"usv": 0, "auv": 0}
        for batch in range(20):
            for i in range(20):
                relays.auv_udp.sendto(b"a%d" % i, (radio_link.RADIO_HOST, relays.usv_port))
                relays.usv_udp.sendto(b"u%d" % i, (peer[0], relays.auv_port))
            quiet = 0  # reads that found nothing on either socket; the radio delivers 0.5 ms after a read
            while quiet < (2 if batch < 19 else 10):
                got_any = False
                for name, s in (("usv", relays.usv_udp), ("auv", relays.auv_udp)):
                    try:
                        data, source = s.recvfrom(100)
                    except socket.timeout:
                        continue
                    got_any = True
                    assert source[0] == radio_link.RADIO_HOST
                    # the source each relay accepts: the AUV's datagrams from its peer's UDP port at the radio, the
                    # USV's from the AUV's UDP port at the radio
                    assert source[1] == (relays.auv_port if name == "usv" else relays.usv_port)
                    received[name] += 1
                quiet = 0 if got_any else quiet + 1
        stats = radio.stats()
        for name, channel in (("usv", "to_usv"), ("auv", "to_auv")):  # 5 % lost on average
            c = stats[channel]
            assert 0.85 * 400 < received[name] < 400, (received, stats)
            # every datagram the radio did not lose arrived
            assert received[name] == 400 - c["lost"] - c["dropped_queue"], (received, stats)
        assert stats["to_usv"]["retransmitted"] > 0 and stats["to_usv"]["lost"] > 0
        # the link fault: the connection is dropped, datagrams are lost, a new connection is refused
        radio.down()
        assert closed(usv) and closed(auv)
        relays.auv_udp.sendto(b"lost", (radio_link.RADIO_HOST, relays.usv_port))
        with pytest.raises(socket.timeout):
            relays.usv_udp.recvfrom(100)
        with pytest.raises(OSError):
            socket.create_connection((radio_link.RADIO_HOST, relays.usv_port), timeout=1.0)
        radio.up()
        auv, usv, _ = relays.connect()
        auv.sendall(b"back")
        assert usv.recv(10) == b"back"
    finally:
        radio.close()
        relays.close()
