"""tse.can's side of stream.sh: a trajectory file streamed N times in a row, each to its last row
(prints the rows per second of each run), or a file the controller would refuse, refused before
anything is sent (prints the row).
Usage: python3 stream_client.py run N FILE | python3 stream_client.py refuse FILE"""
import sys

from tse import can as tcan


def rows_of(path):
    with open(path) as f:
        return [tuple(float(v) for v in line.split(",")) for line in f if line[:1] not in ("t", "#", "\n")]


def main():
    what, path = sys.argv[1], sys.argv[-1]
    rows = rows_of(path)
    with tcan.Controller("vcan0", node=1, timeout=10.0) as ctl:
        if what == "refuse":
            try:
                ctl.trajectory(rows)
            except tcan.Rejected as e:
                print(f"tse.can refused row {e.row} (0-based): {e}")
                return 0
            print("tse.can streamed a file it should have refused")
            return 1
        for k in range(int(sys.argv[2])):
            try:
                done = ctl.trajectory(rows)
            except tcan.TseError as e:
                print(f"run {k + 1}: {type(e).__name__}: {e}")
                return 1
            fill = f", {done.fill_rows_per_s:.0f} rows/s until the queue filled" if done.fill_rows_per_s else ""
            print(f"run {k + 1}: {done.rows} rows streamed in {done.seconds:.2f} s ({done.rows_per_s:.0f} rows/s{fill})")
    return 0


sys.exit(main())
