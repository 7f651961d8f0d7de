# The harness's own test scenario (harness_test.sh): it reads the data files it was given, leaves a
# process in the background, then hangs; the harness must stop it and name the hanging line.
echo $$ >scenario.pid
echo "data: $(cat token.txt)"
echo "params: $(cat params.txt)"
echo "binary: $(command -v tse-sim >/dev/null && echo on PATH)"
echo "a line on stderr" >&2
sleep 999 &
sleep 1000
echo "not reached"
