# Issue 28 on the bus: tsectl flash against tse-boot-sim (the bootloader's logic with a file for its
# flash).  A blank board takes an image and starts it; the next update goes over the first; an
# image for another board is refused before anything is erased, a damaged one before anything is
# sent; the figures of the transfer are printed.
pass=0
fail=0
check() { if eval "$2"; then pass=$((pass + 1)); echo "ok: $1"; else fail=$((fail + 1)); echo "FAIL: $1"; fi; }
T="tsectl --iface vcan0 --node 3 --timeout 5000"
# Waits for a bootloader to end (after BOOT_START), 20 s at most, then ends it.
ended() { n=0; while kill -0 "$1" 2>/dev/null && [ $n -lt 100 ]; do sleep 0.2; n=$((n + 1)); done; kill "$1" 2>/dev/null; wait "$1"; }

candump -t d vcan0 >dump.log &
dump=$!
tse-boot-sim --iface vcan0 --node 3 --flash board.flash >boot1.log 2>&1 &
boot=$!
sleep 1
$T flash app1.img >flash1.log 2>&1
rc1=$?
ended $boot
check "a blank board's bootloader stays on the bus" "grep -q 'in the bootloader' boot1.log"
check "tsectl flash app1.img exits 0" "[ $rc1 -eq 0 ]"
check "the bootloader reported no application first" "grep -q 'no application' flash1.log"
check "verified: application 0.1.0" "grep -q 'verified: application 0.1.0' flash1.log"
check "the bootloader starts application 0.1.0 after BOOT_START" "grep -q 'starting the application 0.1.0' boot1.log"
check "a restart starts it without an update" "tse-boot-sim --iface vcan0 --node 3 --flash board.flash | grep -q 'starting the application 0.1.0'"

tse-boot-sim --iface vcan0 --node 3 --flash board.flash --stay >boot2.log 2>&1 &
boot=$!
sleep 1
cp board.flash before-foreign.flash
$T flash foreign.img >foreign.log 2>&1
rcf=$?
check "an image for another board exits 3" "[ $rcf -eq 3 ]"
check "... naming both boards, nothing erased" "grep -q 'for board olimex-e407.*nothing erased' foreign.log"
check "... the flash untouched" "cmp -s board.flash before-foreign.flash"
$T flash damaged.img >damaged.log 2>&1
rcd=$?
check "a damaged image exits 2 with nothing sent" "[ $rcd -eq 2 ] && grep -q 'damaged image' damaged.log"
$T flash app2.img >flash2.log 2>&1
rc2=$?
ended $boot
check "tsectl flash app2.img over 0.1.0 exits 0" "[ $rc2 -eq 0 ]"
check "the bootloader reported application 0.1.0 before" "grep -q 'application 0.1.0 (crc' flash2.log"
check "verified: application 0.2.0" "grep -q 'verified: application 0.2.0' flash2.log"
check "the bootloader starts application 0.2.0" "grep -q 'starting the application 0.2.0' boot2.log"

# A frame lost in the middle of block 1 (the 200th frame the bootloader takes: BOOT_QUERY, ERASE,
# block 0's 129, then block 1's): block 1 is refused `length` when block 2's BOOT_WRITE finds it
# open, block 2 `order` behind it, and tsectl sends again from block 1.
tse-boot-sim --iface vcan0 --node 3 --flash board.flash --stay --drop 200 >boot5.log 2>&1 &
boot=$!
sleep 1
$T flash app1.img >lost.log 2>&1
rcl=$?
ended $boot
check "a lost frame: the bootloader lost it" "grep -q 'frame 200 .* lost' boot5.log"
check "... tsectl sends again from the refused block and completes" "[ $rcl -eq 0 ] && grep -q 'block 1 refused (length), sending again' lost.log && grep -q 'verified: application 0.1.0' lost.log"

# From a running application (tse-sim as node 3): refused while its drives are on; once disabled,
# BOOT_ENTER restarts it into the bootloader (here: tse-sim ends, tse-boot-sim --stay starts, as a
# board restarts), and the update goes through.
( tse-sim --iface vcan0 --node 3 >sim.log 2>&1; tse-boot-sim --iface vcan0 --node 3 --flash board.flash --stay >boot3.log 2>&1 ) &
sleep 1
$T heartbeat >/dev/null 2>&1 &
hb=$!
$T enable >/dev/null 2>&1
$T flash app1.img >enabled.log 2>&1
rce=$?
check "flash while the drives are on exits 3, the application kept" "[ $rce -eq 3 ] && grep -q 'stays in its application' enabled.log"
$T disable >/dev/null 2>&1
kill $hb
$T flash app1.img >flash3.log 2>&1
rc3=$?
check "after disable: the application restarts into its bootloader" "grep -q 'BOOT_ENTER taken' sim.log && grep -q 'asking it to restart' flash3.log"
check "... and tsectl flash app1.img exits 0" "[ $rc3 -eq 0 ] && grep -q 'verified: application 0.1.0' flash3.log"
sleep 0.5
check "... the bootloader starts application 0.1.0" "grep -q 'starting the application 0.1.0' boot3.log"

# tse.can's Controller.flash: app2 over app1, the bootloader staying as after BOOT_ENTER, a frame
# of block 1 lost (the BOOT_QUERY of the foreign image's refusal counts as frame 1).
tse-boot-sim --iface vcan0 --node 3 --flash board.flash --stay --drop 201 >boot4.log 2>&1 &
boot=$!
sleep 1
python3 - >py.log 2>&1 <<'PY'
from tse.can import Controller, Rejected
with Controller("vcan0", node=3, heartbeat=False, timeout=5.0) as c:
    try:
        c.flash("foreign.img")
        print("foreign: taken")
    except Rejected as e:
        print("foreign: refused:", e)
    r = c.flash("app2.img")
    print("python flash: version %d.%d.%d crc 0x%08x erase %.2f s transfer %.3f s %.0f B/s" % (*r.version, r.crc, r.erase_s, r.transfer_s, r.rate))
PY
ended $boot
check "tse.can refuses the foreign image naming the boards" "grep -q 'foreign: refused: the image is for board olimex-e407' py.log"
check "tse.can Controller.flash app2.img: version 0.2.0" "grep -q 'python flash: version 0.2.0' py.log"
check "... a frame of block 1 lost on the way and the block sent again" "grep -q 'frame 201 .* lost' boot4.log"
check "... and the bootloader starts 0.2.0" "grep -q 'starting the application 0.2.0' boot4.log"
kill $dump
check "BOOT_DATA frames on the bus (id 0x7E3)" "grep -q ' 7E3 ' dump.log"
echo "--- tsectl flash app1.img"
cat flash1.log
echo "--- tsectl flash app2.img"
cat flash2.log
echo "--- tse.can"
cat py.log
grep -h "^transfer\|^rate\|^erased" flash1.log flash2.log flash3.log | sed 's/^/figure: /'
grep -h "^python flash" py.log | sed 's/^/figure: /'
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
