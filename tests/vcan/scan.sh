# Finding and renumbering controllers (issue 26 pt 4; docs/board.md, "Node id and ENABLE level"):
# two simulators on one bus, one taking its node id from its parameter file (3), one from --node
# (7); `tsectl scan` and tse.can.scan find both with the firmware's version (tsectl's own), the
# board (tse-sim) and the rates; `tsectl node set` refuses an id another controller answers on,
# sets and saves a free one, the controller answering on its old id until it restarts and on the
# new one after; scan on a bus where nobody answers exits 4 saying so.
pass=0
fail=0
check() { if eval "$2"; then pass=$((pass + 1)); echo "ok: $1"; else fail=$((fail + 1)); echo "FAIL: $1"; fi; }
# Answer waits as e2e.sh's: 5 s times how much slower the VM runs now (1 on vcan0 directly).
answer_ms=$(awk -v s="${TSE_VM_SLOW:-1}" 'BEGIN { printf "%d", 5000 * s }')
version=$(tsectl --version | cut -d' ' -f2)
row() { # node: the scan row of a tse-sim at the built-in rates
  echo "^ *$1  $version +tse-sim +200000 Hz steps, 1000 Hz segments\$"
}

printf '# node from the file\nnode = 3\n' >a.params
tse-sim --iface vcan0 --params a.params >a.log 2>&1 &
a=$!
tse-sim --iface vcan0 --node 7 >b.log 2>&1 &
b=$!
sleep 1
check "the simulator without --node takes its node from the parameter file" "grep -q 'tse-sim: node 3 on vcan0' a.log"

tsectl --iface vcan0 --timeout "$answer_ms" scan >scan.txt 2>&1; rc=$?
sed 's/^/  | /' scan.txt
check "scan exits 0" "[ $rc -eq 0 ]"
check "scan finds node 3 with the firmware's version, its board and rates" "grep -Eq \"$(row 3)\" scan.txt"
check "scan finds node 7 likewise" "grep -Eq \"$(row 7)\" scan.txt"
check "scan finds those two and no other" "[ \$(grep -Ec '^ *[0-9]+  ' scan.txt) -eq 2 ] && grep -q '^2 controllers answered' scan.txt"

python3 -c "
import tse.can as c
for f in c.scan('vcan0', timeout=$answer_ms / 1000):
    print(f.node, '.'.join(map(str, f.version)), f.board, f.step_hz, f.segment_hz)
" >py.txt 2>&1; rc=$?
sed 's/^/  | /' py.txt
check "tse.can.scan finds the same two" "[ $rc -eq 0 ] && [ \"\$(cat py.txt)\" = \"\$(printf '3 %s tse-sim 200000 1000\n7 %s tse-sim 200000 1000' $version $version)\" ]"

T="tsectl --iface vcan0 --node 3 --timeout $answer_ms"
$T node set 7 >out.txt 2>&1; rc=$?
check "node set to an id another controller answers on is refused (exit 3)" \
  "[ $rc -eq 3 ] && grep -q 'node id 7 is taken: a controller already answers on it' out.txt"
$T params get node >out.txt 2>&1
check "... and nothing changed" "grep -qx 'node = 3' out.txt"
$T node set 5 >out.txt 2>&1; rc=$?
sed 's/^/  | /' out.txt
check "node set 5 sets and saves, saying to address it as --node 5 after its restart" \
  "[ $rc -eq 0 ] && grep -q 'node 3: node id 5 set and saved; it takes effect at the controller.s restart: address it as --node 5 afterwards' out.txt"
check "the parameter file holds node = 5" "grep -Eq '^node *= *5' a.params"
$T params get node >out.txt 2>&1; rc=$?
check "until it restarts it answers on node 3, PARAM_GET showing the stored 5" "[ $rc -eq 0 ] && grep -qx 'node = 5' out.txt"
tsectl --iface vcan0 --node 5 --timeout 1000 info >out.txt 2>&1; rc=$?
check "nothing answers on node 5 yet (exit 4)" "[ $rc -eq 4 ]"

kill -INT $a
wait $a
tse-sim --iface vcan0 --params a.params >a2.log 2>&1 &
a=$!
sleep 1
check "restarted, the simulator takes node 5" "grep -q 'tse-sim: node 5 on vcan0' a2.log"
tsectl --iface vcan0 --node 5 --timeout "$answer_ms" info >out.txt 2>&1; rc=$?
check "it answers on node 5" "[ $rc -eq 0 ] && grep -q '^node 5: firmware $version' out.txt"
tsectl --iface vcan0 --timeout "$answer_ms" scan >scan.txt 2>&1; rc=$?
sed 's/^/  | /' scan.txt
check "scan finds nodes 5 and 7, not 3" \
  "[ $rc -eq 0 ] && grep -Eq \"$(row 5)\" scan.txt && grep -Eq \"$(row 7)\" scan.txt && ! grep -Eq '^ *3  ' scan.txt"

tsectl --iface vcan0 --node 5 --timeout "$answer_ms" params set enable_level 2 >out.txt 2>&1; rc=$?
check "params set of a parameter taken at start-up says it is not yet in effect" \
  "[ $rc -eq 0 ] && grep -qx 'enable_level = 2' out.txt && grep -q '^# stored, not yet in effect: node 5 takes enable_level at start-up' out.txt"

kill -INT $a $b
wait $a $b
tsectl --iface vcan0 --timeout 500 scan >scan.txt 2>&1; rc=$?
check "scan with no controller on the bus exits 4 saying so" "[ $rc -eq 4 ] && grep -q 'no controller answered' scan.txt"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
