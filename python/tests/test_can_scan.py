"""tse.can.scan and Controller.set_node on the host, on python-can's in-process virtual bus: small
responders answer INFO_GET as docs/protocol.md lays the frames out (id = function << 4 | node;
INFO 0x29: major, minor, patch, step_hz u24, segment_hz u16; BOARD 0x2B: eight ASCII bytes, NUL
after the name; REJECT 0x03: function, seq, reason, ...), written here byte by byte, not through
the codec.  The real controllers (tse-sim on vcan) are scanned in the vcan harness (tests/vcan/scan.sh)."""
import os
import threading
import warnings

import can as pycan
import pytest

from tse import can as tcan

from fake_controller import Recorder

INFO_GET, INFO, BOARD, ACK, REJECT = 0x12, 0x29, 0x2B, 0x04, 0x03
REASON_UNKNOWN, REASON_RANGE = 2, 3  # docs/protocol.md, "reject reason"


class Responder:
    """Answers INFO_GET to `node` on the virtual channel: page 0 with `info` bytes (or refused
    unknown when None), page 1 with `board` bytes (or refused range when None); `twice` answers
    INFO twice, as two controllers on one id would."""

    def __init__(self, channel, node, info, board, twice=False):
        self.node, self.info, self.board, self.twice = node, info, board, twice
        self.bus = pycan.Bus(interface="virtual", channel=channel, receive_own_messages=False)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _send(self, function, data):
        self.bus.send(pycan.Message(arbitration_id=function << 4 | self.node, is_extended_id=False, data=data))

    def _run(self):
        while not self._stop.is_set():
            f = self.bus.recv(0.02)
            if f is None or f.arbitration_id != (INFO_GET << 4 | self.node) or len(f.data) != 1:
                continue
            page = f.data[0]
            answer = self.info if page == 0 else self.board
            if answer is None:
                reason = REASON_UNKNOWN if self.info is None else REASON_RANGE
                self._send(REJECT, bytes([INFO_GET, 0, reason, 0, 0, 0, 0, 0]))
                continue
            self._send(ACK, bytes([INFO_GET, 0, 0, 32, 0, 0, 0, 0]))
            for _ in range(2 if self.twice and page == 0 else 1):
                self._send(INFO if page == 0 else BOARD, answer)

    def close(self):
        self._stop.set()
        self._thread.join()
        self.bus.shutdown()


# 1.2.3 at 200000 Hz (0x030D40) and 1000 Hz (0x03E8), little-endian.
INFO_123 = bytes([1, 2, 3, 0x40, 0x0D, 0x03, 0xE8, 0x03])
# 0.1.0 at 100000 Hz (0x0186A0) and 2000 Hz (0x07D0).
INFO_010 = bytes([0, 1, 0, 0xA0, 0x86, 0x01, 0xD0, 0x07])


@pytest.fixture
def channel():
    return f"tse-scan-{os.getpid()}-{threading.get_ident()}"


def scanning(channel, responders, timeout=0.5):
    bus = pycan.Bus(interface="virtual", channel=channel, receive_own_messages=False)
    try:
        return tcan.scan(bus, timeout=timeout)
    finally:
        bus.shutdown()
        for r in responders:
            r.close()


def test_scan_finds_every_node_with_its_version_board_and_rates(channel):
    rs = [Responder(channel, 2, INFO_123, b"gen_f405"), Responder(channel, 9, INFO_010, b"tse-sim\0"),
          Responder(channel, 15, INFO_010, None)]  # a firmware older than BOARD: page 1 refused range
    found = scanning(channel, rs)
    assert found == [tcan.Found(2, (1, 2, 3), "gen_f405", 200000, 1000),
                     tcan.Found(9, (0, 1, 0), "tse-sim", 100000, 2000),
                     tcan.Found(15, (0, 1, 0), None, 100000, 2000)]


def test_scan_of_a_firmware_older_than_info_names_the_node_only(channel):
    found = scanning(channel, [Responder(channel, 4, None, None)])
    assert found == [tcan.Found(4, None, None, None, None)]


def test_scan_asks_every_node_both_pages_and_finds_none_on_a_silent_bus(channel):
    spy = pycan.Bus(interface="virtual", channel=channel)
    rec = Recorder()
    notifier = pycan.Notifier(spy, [rec], timeout=0.02)
    try:
        assert scanning(channel, [], timeout=0.2) == []
    finally:
        notifier.stop()
        spy.shutdown()
    asked = sorted((f.arbitration_id, bytes(f.data)) for f in rec.frames)
    assert asked == sorted((INFO_GET << 4 | n, bytes([p])) for n in range(1, 16) for p in (0, 1))


def test_two_controllers_on_one_id_are_warned_about(channel):
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        found = scanning(channel, [Responder(channel, 6, INFO_123, b"ab\0\0\0\0\0\0", twice=True)])
    assert found == [tcan.Found(6, (1, 2, 3), "ab", 200000, 1000)]
    assert any("two controllers share node id 6" in str(x.message) for x in w)


def test_scan_refuses_a_bad_timeout():
    with pytest.raises(ValueError, match="timeout 0 is not a positive number"):
        tcan.scan("vcan0", timeout=0)


def test_set_node_out_of_range_sends_nothing(channel):
    ctl_bus = pycan.Bus(interface="virtual", channel=channel, receive_own_messages=False)
    spy = pycan.Bus(interface="virtual", channel=channel)
    rec = Recorder()
    notifier = pycan.Notifier(spy, [rec], timeout=0.02)
    ctl = tcan.Controller(node=3, timeout=0.3, heartbeat=False, bus=ctl_bus)
    try:
        for bad in (0, 16, -1, 5.0, "5", True):
            with pytest.raises(ValueError, match=r"is not a node id: a whole number 1\.\.15 \(nothing sent\)"):
                ctl.set_node(bad)
        assert rec.frames == []
    finally:
        ctl.close()
        notifier.stop()
        spy.shutdown()
        ctl_bus.shutdown()
