#!/usr/bin/env bash
# Static analysis of kinematics/, firmware/, hal/, host_tools/ and boot/ (sources and the headers they
# include): cppcheck and clang-tidy, each with the compile commands of the real builds, so both
# precisions, the host's POSIX code and the board's register code are analysed as compiled.
#   - host:  a host configure (tse_kin_d and tse_kin_f, firmware in double, hal/posix, the tools);
#   - board: a stm32f4 configure (firmware in float, hal/stm32f4 with its drivers and startup),
#            given to clang-tidy as --target=arm-none-eabi with newlib's headers.
# Any finding fails the script.  Findings are fixed, or suppressed where they are false
# positives: inline (cppcheck-suppress / NOLINT, with the reason) when the reason is local,
# .cppcheck-suppressions or .clang-tidy when it is not.
# Needs: cppcheck (2.10), clang-tidy (14), cmake, gcc, gcc-arm-none-eabi, libnewlib-arm-none-eabi,
# python3.  Output: build/static (TSE_STATIC_DIR), the full logs there.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
out=${TSE_STATIC_DIR:-$root/build/static}
jobs=$(nproc 2>/dev/null || echo 2)
start=$SECONDS

for tool in cppcheck clang-tidy cmake python3 arm-none-eabi-gcc; do
  command -v "$tool" >/dev/null || { echo "static: $tool not found (scripts/setup.sh installs it)" >&2; exit 2; }
done

mkdir -p "$out"
# Configure only: nothing is generated at build time, so the compile databases are complete.
for preset in host stm32f4 cortex-m3; do
  cmake --preset "$preset" -B "$out/$preset" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DTSE_CCACHE=OFF -DBUILD_TESTING=OFF \
    >"$out/configure-$preset.log" 2>&1 ||
    { cat "$out/configure-$preset.log" >&2; echo "static: the $preset configure failed" >&2; exit 2; }
done

# newlib's headers, as the cross compiler finds them (clang-tidy brings its own stddef.h etc.).
newlib_inc=$(echo | arm-none-eabi-gcc -xc -E -v - 2>&1 | sed -n '/^#include <...>/,/^End of search/p' |
  sed -n 's/^ //p' | while read -r d; do readlink -f "$d"; done | grep -v '/gcc/' | head -n1)
[ -f "$newlib_inc/stdint.h" ] || { echo "static: newlib headers not found (libnewlib-arm-none-eabi)" >&2; exit 2; }

# The databases, cut to the analysed folders; the board's rewritten for clang.  Fails when a
# source under the folders is in neither build, or a header is included by nothing analysed.
python3 - "$root" "$out" "$newlib_inc" <<'EOF'
import json, os, re, shlex, sys
root, out, newlib = sys.argv[1:]
dirs = ('kinematics', 'firmware', 'hal', 'host_tools', 'boot')

def ours(path):
    rel = os.path.relpath(path, root)
    return rel.split(os.sep)[0] in dirs and not rel.startswith('..')

def load(build):
    with open(os.path.join(out, build, 'compile_commands.json')) as f:
        return [e for e in json.load(f) if ours(e['file'])]

def write(path, entries):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w') as f:
        json.dump(entries, f, indent=1)

def args_of(e):
    return e['arguments'] if 'arguments' in e else shlex.split(e['command'])

host, board = load('host'), load('stm32f4')
# The Cortex-M3 build's own sources (hal/mps2: its start-up and counter) with the board's: the
# same cross compiler and analyses; what it shares with the other builds is analysed there.
known = {e['file'] for e in host + board}
board += [e for e in load('cortex-m3') if e['file'] not in known]
write(os.path.join(out, 'cppcheck', 'host.json'), host)
write(os.path.join(out, 'cppcheck', 'board.json'), board)
write(os.path.join(out, 'tidy', 'host', 'compile_commands.json'), host)
# gcc-only options clang rejects (-fstack-usage, -fcallgraph-info: the stack report's) go; the
# target and newlib come in.  <stdint.h> first: clang's <stdatomic.h> defers to newlib's (gcc
# uses its own), which names int_least8_t and the like without including it.
clang_board = []
for e in board:
    a = [x for x in args_of(e) if x != '-fstack-usage' and not x.startswith('-fcallgraph-info')]
    a[1:1] = ['--target=arm-none-eabi', '-isystem', newlib, '-include', 'stdint.h']
    clang_board.append({'directory': e['directory'], 'file': e['file'], 'arguments': a})
write(os.path.join(out, 'tidy', 'board', 'compile_commands.json'), clang_board)

# clang-tidy: every host source; from the board, what the host does not compile alike (the float
# firmware, the board's drivers; its kinematics is tse_kin_f, analysed on the host already).
# Largest first, so that the last files to start are short ones.
jobs = {('host', e['file']) for e in host}
jobs |= {('board', e['file']) for e in board if not os.path.relpath(e['file'], root).startswith('kinematics')}
with open(os.path.join(out, 'tidy', 'jobs'), 'w') as f:
    for build, p in sorted(jobs, key=lambda j: (-os.path.getsize(j[1]), j)):
        f.write(build + '\n' + p + '\n')

sources = {e['file'] for e in host + board}
missing = []
headers = set()
for d in dirs:
    for base, _, names in os.walk(os.path.join(root, d)):
        for n in names:
            p = os.path.join(base, n)
            if n.endswith('.c') and p not in sources:
                missing.append(os.path.relpath(p, root))
            if n.endswith('.h'):
                headers.add(p)

# The headers the analysed sources include, directly or not: "..." includes resolved against the
# including file's folder and the entry's -I folders, as the compiler does.
inc_re = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)
reached = set()
for e in host + board:
    a = args_of(e)
    incs = [x[2:] for x in a if x.startswith('-I') and len(x) > 2]
    incs += [a[i + 1] for i, x in enumerate(a[:-1]) if x in ('-I', '-isystem')]
    incs = [os.path.normpath(os.path.join(e['directory'], x)) for x in incs]
    todo = [os.path.normpath(os.path.join(e['directory'], e['file']))]
    # A board description comes in through a macro (src/board_desc.c: #include TSE_BOARD_HEADER).
    todo += [x.split('=', 1)[1].strip('"\\') for x in a if x.startswith('-DTSE_BOARD_HEADER=')]
    seen = set()
    while todo:
        p = todo.pop()
        if p in seen:
            continue
        seen.add(p)
        with open(p, errors='replace') as f:
            text = f.read()
        for name in inc_re.findall(text):
            for d in [os.path.dirname(p)] + incs:
                q = os.path.normpath(os.path.join(d, name))
                if os.path.isfile(q):
                    todo.append(q)
                    break
    reached |= seen
missing += sorted(os.path.relpath(h, root) for h in headers - reached)
if missing:
    print('static: not in any analysed build (add it to a CMakeLists.txt, or delete it):', file=sys.stderr)
    for m in sorted(missing):
        print('  ' + m, file=sys.stderr)
    sys.exit(1)
with open(os.path.join(out, 'counts'), 'w') as f:
    print(len(host) + len(board), len(sources), len(headers & reached), len(jobs), file=f)
EOF
read -r n_tu n_src n_hdr n_tidy_files <"$out/counts"

# cppcheck: the board is ILP32 with an unsigned char (AAPCS), which unix32 is not.
cat >"$out/cppcheck/arm-eabi.xml" <<'EOF'
<?xml version="1.0"?>
<platform>
  <char_bit>8</char_bit>
  <default-sign>unsigned</default-sign>
  <sizeof>
    <bool>1</bool>
    <short>2</short>
    <int>4</int>
    <long>4</long>
    <long-long>8</long-long>
    <float>4</float>
    <double>8</double>
    <long-double>8</long-double>
    <pointer>4</pointer>
    <size_t>4</size_t>
    <wchar_t>4</wchar_t>
  </sizeof>
</platform>
EOF
cppcheck_run() { # BUILD PLATFORM [ARGS...]
  local build=$1 platform=$2
  shift 2
  cppcheck -q -j "$jobs" --std=c11 --enable=warning,performance,portability --inline-suppr \
    --suppressions-list="$root/.cppcheck-suppressions" --platform="$platform" "$@" \
    --project="$out/cppcheck/$build.json" --error-exitcode=0 \
    --template='{file}:{line}:{column}: {severity}: {message} [{id}]' 2>&1 ||
    echo "cppcheck failed on the $build build (exit $?)"
}
t0=$SECONDS
{
  cppcheck_run host unix64 --library=posix
  cppcheck_run board "$out/cppcheck/arm-eabi.xml"
} >"$out/cppcheck.log"
t_cppcheck=$((SECONDS - t0))
# Every line of cppcheck -q's is a finding, or its own error (a file it could not read...).
cppcheck_findings=$(grep -v '^$' "$out/cppcheck.log" | sort -u || true)
n_cppcheck=$(printf '%s' "$cppcheck_findings" | grep -c . || true)

# clang-tidy: one file per process, each into its own log.  (Given several files, LLVM 14's
# analyzer carries state from one to the next: clang-analyzer-valist.Uninitialized then reports
# every va_list passed to vsnprintf after the first file.)
rm -rf "$out/tidy/logs"
mkdir -p "$out/tidy/logs"
t0=$SECONDS
# shellcheck disable=SC2016
xargs -a "$out/tidy/jobs" -d '\n' -n 2 -P "$jobs" sh -c \
  'log="$0/tidy/logs/$2_$(echo "$3" | tr / _).log"
   clang-tidy -p "$0/tidy/$2" --config-file="$1/.clang-tidy" --quiet "$3" >"$log" 2>&1 ||
     echo "exit $?" >>"$log"' "$out" "$root" || true
t_tidy=$((SECONDS - t0))
n_logs=$(find "$out/tidy/logs" -name '*.log' | wc -l)
[ "$n_logs" -eq "$n_tidy_files" ] ||
  { echo "static: clang-tidy ran on $n_logs of $n_tidy_files translation units" >&2; exit 2; }
cat "$out"/tidy/logs/*.log >"$out/clang-tidy.log"
# A finding's first line (some messages run on over several lines); a header's findings come
# once per file that includes it, counted once.
tidy_re='^[^ ]+:[0-9]+:[0-9]+: (warning|error): '
tidy_findings=$(grep -hE "$tidy_re" "$out"/tidy/logs/*.log | sort -u || true)
n_tidy=$(printf '%s' "$tidy_findings" | grep -c . || true)
# A file clang-tidy failed on without a finding located in it (an unknown option...): its log.
tidy_broken=()
for log in "$out"/tidy/logs/*.log; do
  if grep -q '^exit ' "$log" && ! grep -qE "$tidy_re" "$log"; then
    tidy_broken+=("$log")
  fi
done

status=0
if [ "$n_cppcheck" -gt 0 ]; then
  printf '%s\n' "$cppcheck_findings" >&2
  status=1
fi
if [ "$n_tidy" -gt 0 ]; then
  printf '%s\n' "$tidy_findings" >&2
  echo "(clang-tidy's explanations: $out/clang-tidy.log)" >&2
  status=1
fi
for log in "${tidy_broken[@]}"; do
  echo "clang-tidy failed: $log" >&2
  cat "$log" >&2
  status=1
done

echo "cppcheck $(cppcheck --version | awk '{print $2}'): $n_tu translation units ($n_src sources, $n_hdr headers), $n_cppcheck findings, ${t_cppcheck} s"
echo "clang-tidy $(clang-tidy --version | awk '/version/ {print $NF; exit}'): $n_tidy_files translation units (their headers included), $n_tidy findings, ${t_tidy} s"
echo "static: $((SECONDS - start)) s, $([ $status -eq 0 ] && echo passed || echo FAILED)"
exit $status
