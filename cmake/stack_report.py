#!/usr/bin/env python3
"""Worst-case stack of a board image, from GCC's -fstack-usage / -fcallgraph-info=su output.

    stack_report.py --map IMAGE.map --build-dir DIR [--elf IMAGE.elf] [--report FILE]
                    [--source-root DIR] [--prio-header pinmap.h ...] [--json FILE] [--quiet]

Reads the image's link map (which objects and which function sections the linker kept; the
reserved stack `_stack_size`), the .ci call graph and the .su frames that GCC wrote beside each
linked object of the build directory, and the relocations of those objects (calls the call graph
does not see, such as a branch in inline assembly, and which functions have their address taken).
It then computes:
  - each function's own frame;
  - the deepest call chain from the thread root (Reset_Handler, else main) and from every
    exception handler in the image (names ending in _Handler or _IRQHandler);
  - the worst case of the whole stack: the thread's deepest chain, plus for each distinct
    exception priority level the deepest handler of that level and one exception frame;
and compares it with `_stack_size`.  Exit status 1, with a message, when the worst case exceeds
the reservation or cannot be bounded (recursion, a dynamic frame, missing call graphs).  The
report goes to IMAGE.stack.txt beside the .elf; the summary lines are printed.

Conservative rules (the report repeats them):
  - Indirect calls (the node "__indirect_call").  The possible targets are the functions of the
    image whose address is taken outside the vector table (from the relocations), or that nothing
    in the call graph calls.  Each call site (the .ci gives its source position) is narrowed to
    the targets C allows through that pointer: as many parameters as the call has arguments, and
    void or not as the pointer's declaration (every declaration `R (*name)(...)`, or through a
    typedef, of the called member or variable's name in the sources; all of them if several).
    A site that cannot be read keeps every target.  A chain does not enter the same target twice
    (no recursion through function pointers).  The report also gives the figure without the
    narrowing (every target at every indirect call).
  - A function with no call graph (newlib, libgcc, assembly) counts as one frame of
    --library-allowance bytes (--small-allowance for mem*/str* routines and __aeabi helpers) and
    calls nothing of the firmware, except qsort and bsearch which may make an indirect call.
  - Priorities: tse_nvic_enable(IRQ_X, P) in the linked sources puts X_IRQHandler at level P
    (a number, or a macro of that source or of a --prio-header).  NMI is level -2, HardFault -1,
    the other system handlers keep their reset priority 0.  A handler whose priority is not
    found gets a level of its own.  One handler per level can be active at a time; each level
    adds an exception frame (FPU context in use, lazy stacking: 26 words) and 4 bytes of
    alignment.
Python standard library only.
"""
import argparse
import json
import os
import re
import struct
import sys

# newlib's deepest chains, measured by disassembly in this toolchain's libraries (Debian's
# arm-none-eabi 12, nano, thumb/v7e-m+fp/hard): sinf and cosf 480 bytes (__kernel_rem_pio2f holds
# 416), vsnprintf about 370, atan2f 32, asinf 48; memcpy 0, memset 12, memmove 16, strcmp 16, the
# __aeabi helpers 0..32.
LIBRARY_ALLOWANCE = 512
SMALL_ALLOWANCE = 64
SMALL_LIBRARY = re.compile(r"^(mem(cpy|set|move|cmp|chr)|str(cmp|ncmp|len|nlen|cpy|ncpy|chr))$|^__aeabi_")
EXCEPTION_FRAME = 104  # Cortex-M4F with the FPU context: 8 + 18 words (lazy stacking reserves it)
ALIGN_PAD = 4  # CCR.STKALIGN: the frame may start 4 bytes lower to be 8-byte aligned
VECTOR_SECTIONS = (".isr_vector",)
CALLBACK_LIBRARY = ("qsort", "bsearch")
INDIRECT = "__indirect_call"
CORE_LEVELS = {"NMI_Handler": -2, "HardFault_Handler": -1}
CORE_RESET_PRIORITY_0 = ("MemManage_Handler", "BusFault_Handler", "UsageFault_Handler", "SVC_Handler",
                         "DebugMon_Handler", "PendSV_Handler", "SysTick_Handler")
TEXT_PREFIXES = (".text.", ".text.startup.", ".text.unlikely.", ".text.hot.", ".text.exit.")
STALE_SECONDS = 120  # GCC writes the .ci before the assembler writes the object: a .ci older
#                     than its object by more than this was not written by the object's compile
MAX_STATES = 500000  # the search through indirect calls gives up (no bound) beyond this


def is_handler(name):
    return name != "Reset_Handler" and (name.endswith("_IRQHandler") or name.endswith("_Handler"))


# ---------------------------------------------------------------- link map
class LinkMap:
    """Input sections the linker kept and discarded, per object, and the symbols it lists."""

    SEC_FULL = re.compile(r"^ (\S+)\s+0x([0-9a-fA-F]+)\s+0x([0-9a-fA-F]+)\s+(\S.*?)\s*$")
    SEC_NAME = re.compile(r"^ (\S+)\s*$")
    SEC_CONT = re.compile(r"^\s+0x([0-9a-fA-F]+)\s+0x([0-9a-fA-F]+)\s+(\S.*?)\s*$")
    SYMBOL = re.compile(r"^\s+0x([0-9a-fA-F]+)\s+([A-Za-z_.$][\w.$]*)\s*$")
    STACK = re.compile(r"^\s+0x([0-9a-fA-F]+)\s+_stack_size\s*=")

    def __init__(self, path):
        self.kept = {}  # object -> {section name}
        self.discarded = {}
        self.symbols = {}  # name -> (object, section, address)
        self.stack_size = None
        part = None
        pending = None  # a section name whose address and object are on the next line
        current = None  # (object, section) the symbol lines belong to
        with open(path, errors="replace") as f:
            for line in f:
                line = line.rstrip("\n")
                if line.startswith("Discarded input sections"):
                    part = self.discarded
                    continue
                if line.startswith("Memory Configuration"):
                    part = None
                    continue
                if line.startswith("Linker script and memory map"):
                    part = self.kept
                    continue
                m = self.STACK.match(line)
                if m and self.stack_size is None:
                    self.stack_size = int(m.group(1), 16)
                if part is None:
                    continue
                if line and not line[0].isspace():  # an output section: no object
                    pending = current = None
                    continue
                if pending is not None:
                    m = self.SEC_CONT.match(line)
                    name, pending = pending, None
                    if m:
                        current = self._add(part, name, m.group(3))
                        continue
                m = self.SEC_FULL.match(line)
                if m and not m.group(1).startswith("*"):
                    current = self._add(part, m.group(1), m.group(4))
                    continue
                m = self.SEC_NAME.match(line)
                if m and not m.group(1).startswith(("*", "0x")):
                    pending, current = m.group(1), None
                    continue
                m = self.SYMBOL.match(line)
                if m and current is not None and part is self.kept:
                    self.symbols.setdefault(m.group(2), (current[0], current[1], int(m.group(1), 16)))
                elif "=" in line:
                    current = None

    @staticmethod
    def _add(part, section, obj):
        if obj.endswith("(size before relaxing)") or obj.startswith("linker stubs"):
            return None
        part.setdefault(obj, set()).add(section)
        return (obj, section)

    def state(self, obj, section):
        """'kept', 'dropped' or None (the map does not say)."""
        if section in self.kept.get(obj, ()):
            return "kept"
        if section in self.discarded.get(obj, ()):
            return "dropped"
        return None


def stack_size_from_script(path):
    with open(path) as f:
        m = re.search(r"\b_stack_size\s*=\s*(0x[0-9a-fA-F]+|\d+)\s*([KM]?)\s*;", f.read())
    if not m:
        return None
    return int(m.group(1), 0) * {"": 1, "K": 1024, "M": 1024 * 1024}[m.group(2)]


# ---------------------------------------------------------------- relocatable objects (ELF32)
CALL_RELOCS = {1, 10, 28, 29, 30, 51}  # PC24, THM_CALL, CALL, JUMP24, THM_JUMP24, THM_JUMP19
IGNORED_RELOCS = {0, 40, 42}  # NONE, V4BX, PREL31 (unwind tables)


class ElfObject:
    """Sections, function symbols and relocations of one ARM ELF32 little-endian object."""

    def __init__(self, path):
        with open(path, "rb") as f:
            data = f.read()
        if data[:4] != b"\x7fELF" or data[4] != 1 or data[5] != 1:
            raise ValueError("not an ELF32 little-endian object")
        (shoff,) = struct.unpack_from("<I", data, 32)
        shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 46)
        shdrs = [struct.unpack_from("<10I", data, shoff + i * shentsize) for i in range(shnum)]

        def cstr(tab, off):
            start = tab[4] + off
            return data[start:data.index(b"\0", start)].decode(errors="replace")

        self.sections = [cstr(shdrs[shstrndx], h[0]) for h in shdrs]
        self.alloc = [bool(h[2] & 2) for h in shdrs]
        self.funcs = {}  # section index -> [(start, end, name, global)]
        self.symbols = []  # per symbol index: (name, type, section index)
        symtab = next((h for h in shdrs if h[1] == 2), None)
        if symtab is not None:
            names = shdrs[symtab[6]]
            for i in range(symtab[5] // 16):
                st_name, value, size, info, _other, shndx = struct.unpack_from("<IIIBBH", data, symtab[4] + 16 * i)
                name = cstr(names, st_name) if st_name else ""
                self.symbols.append((name, info & 15, shndx))
                if info & 15 == 2 and 0 < shndx < shnum:  # STT_FUNC
                    start = value & ~1
                    self.funcs.setdefault(shndx, []).append((start, start + max(size, 1), name, info >> 4 != 0))
        self.relocs = []  # (section index, offset, type, symbol index)
        for h in shdrs:
            if h[1] == 9:  # SHT_REL
                for i in range(h[5] // 8):
                    off, info = struct.unpack_from("<II", data, h[4] + 8 * i)
                    self.relocs.append((h[7], off, info & 0xFF, info >> 8))

    def function_at(self, shndx, offset):
        for start, end, name, _glob in self.funcs.get(shndx, ()):
            if start <= offset < end:
                return name
        return None


# ---------------------------------------------------------------- call graphs (.ci) and frames (.su)
def unquote(s):
    return s.replace('\\"', '"').replace("\\\\", "\\")


QUOTED = r'"((?:[^"\\]|\\.)*)"'
CI_GRAPH = re.compile(r"^graph: \{ title: " + QUOTED)
CI_NODE = re.compile(r"^node: \{ title: " + QUOTED + " label: " + QUOTED)
CI_EDGE = re.compile(r"^edge: \{ sourcename: " + QUOTED + " targetname: " + QUOTED + "(?: label: " + QUOTED + ")?")
FRAME = re.compile(r"^(\d+) bytes \(([\w,]+)\)$")


def read_ci(path):
    """(source path, {title: (name, location, frame, qualifier)}, [(source, target, location)])"""
    source, nodes, edges = None, {}, []
    with open(path, errors="replace") as f:
        for line in f:
            m = CI_GRAPH.match(line)
            if m:
                source = unquote(m.group(1))
                continue
            m = CI_NODE.match(line)
            if m:
                parts = unquote(m.group(2)).split("\\n")
                frames = [FRAME.match(p) for p in parts[2:]]
                frames = [fm for fm in frames if fm]
                if frames:  # a definition; declarations carry no frame
                    nodes[unquote(m.group(1))] = (parts[0], parts[1] if len(parts) > 1 else "",
                                                  int(frames[0].group(1)), frames[0].group(2))
                continue
            m = CI_EDGE.match(line)
            if m:
                edges.append((unquote(m.group(1)), unquote(m.group(2)), unquote(m.group(3) or "")))
    return source, nodes, edges


def read_su(path):
    """{'file:line:col': {frame}}: clones of one function share a position."""
    out = {}
    with open(path, errors="replace") as f:
        for line in f:
            fields = line.rstrip("\n").split("\t")
            if len(fields) == 3 and fields[1].isdigit():
                out.setdefault(fields[0].rsplit(":", 1)[0], set()).add(int(fields[1]))
    return out


# ---------------------------------------------------------------- C sources: pointer types
def blank_source(text):
    """The text with comments, string and character literals and preprocessor lines blanked to
    spaces: the same length and lines, so that a line:column still points at the same place."""
    out = list(text)
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c in " \t":
            i += 1
            continue
        if line_start and c == "#":  # a directive, with its continuation lines
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out[i] = " "
                    i += 2
                    continue
                out[i] = " "
                i += 1
            continue
        line_start = c == "\n"
        if text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            for j in range(i, end):
                if out[j] != "\n":
                    out[j] = " "
            i = end
            continue
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                out[i] = " "
                i += 1
            continue
        if c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                if text[j] == "\\":
                    out[j] = " "
                    j += 1
                if j < n and text[j] != "\n":
                    out[j] = " "
                j += 1
            i = j + 1
            continue
        i += 1
    return "".join(out)


IDENT = re.compile(r"[A-Za-z_]\w*")
POINTER_DECL = re.compile(r"\(\s*\*\s*(?:(?:const|volatile)\s+)*([A-Za-z_]\w*)\s*(?:\[[^\]]*\]\s*)*\)\s*\(")
FUNC_TYPEDEF = re.compile(r"\btypedef\b([^;{}()]*?)\b([A-Za-z_]\w*)\s*\(")


def matching(text, i):
    """Index just past the bracket that closes the one at text[i], or -1."""
    depth = 0
    while i < len(text):
        if text[i] in "([{":
            depth += 1
        elif text[i] in ")]}":
            depth -= 1
            if depth == 0:
                return i + 1
        i += 1
    return -1


def count_params(inner):
    """(number of parameters or None when unspecified, variadic) of a parameter list's text."""
    s = inner.strip()
    if not s:
        return None, False
    parts, depth, cur = [], 0, ""
    for c in s:
        if c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        if c == "," and depth == 0:
            parts.append(cur)
            cur = ""
        else:
            cur += c
    parts.append(cur)
    parts = [p.strip() for p in parts]
    if parts == ["void"]:
        return 0, False
    if parts[-1] == "...":
        return len(parts) - 1, True
    return len(parts), False


def returns_void(prefix):
    """Whether the declaration text before a name or a (*name) says void (not void *)."""
    prefix = re.sub(r"__attribute__\s*\(\(.*?\)\)", " ", prefix)
    words = IDENT.findall(prefix)
    return "void" in words and "*" not in prefix


def shape_compatible(a, b):
    """Whether a function of shape b may be called through a pointer of shape a (or the other
    way): shapes are (parameters or None, variadic, void or None)."""
    (na, va, ra), (nb, vb, rb) = a, b
    if ra is not None and rb is not None and ra != rb:
        return False
    if na is None or nb is None or va or vb:
        return True
    return na == nb


class Sources:
    """The C sources (comments blanked) and the function pointer declarations in them."""

    def __init__(self, root, extra):
        self.cache = {}
        self.root = root or os.getcwd()  # relative positions start here
        self.files = set(extra)
        if root:
            for dirpath, dirs, files in os.walk(root):
                dirs[:] = [d for d in dirs if not d.startswith(".") and not d.startswith("build")]
                self.files.update(os.path.join(dirpath, f) for f in files if f.endswith((".c", ".h")))
        self._decls = None

    def text(self, path):
        if path not in self.cache:
            try:
                with open(path, errors="replace") as f:
                    self.cache[path] = blank_source(f.read())
            except OSError:
                self.cache[path] = None
        return self.cache[path]

    def at(self, where, built):
        """(text, offset) of 'file:line:col', or (None, None); also when the file changed after
        `built` (the time of the call graph that gave the position)."""
        m = re.match(r"^(.*):(\d+):(\d+)$", where or "")
        if not m:
            return None, None
        path = os.path.join(self.root, m.group(1))
        try:
            if os.path.getmtime(path) > built:
                return None, None
        except OSError:
            return None, None
        text = self.text(path)
        if text is None:
            return None, None
        line, col = int(m.group(2)), int(m.group(3))
        off = 0
        for _ in range(line - 1):
            off = text.find("\n", off)
            if off < 0:
                return None, None
            off += 1
        off += col - 1
        return (text, off) if off < len(text) else (None, None)

    @staticmethod
    def _call_at(text, i):
        """(called name, arguments, start and end of the argument list) of the call expression
        starting at text[i], or None."""
        name = None
        if text[i] == "(":  # (*fp)(...) or (s->fn)(...)
            end = matching(text, i)
            if end < 0:
                return None
            names = IDENT.findall(text[i:end])
            name, i = (names[-1] if names else None), end
        else:
            while True:
                m = IDENT.match(text, i)
                if not m:
                    return None
                name, i = m.group(0), m.end()
                while i < len(text) and text[i] in " \t\n":
                    i += 1
                while text.startswith("[", i):
                    i = matching(text, i)
                    if i < 0:
                        return None
                    while i < len(text) and text[i] in " \t\n":
                        i += 1
                if text.startswith(".", i):
                    i += 1
                elif text.startswith("->", i):
                    i += 2
                else:
                    break
                while i < len(text) and text[i] in " \t\n":
                    i += 1
        while i < len(text) and text[i] in " \t\n":
            i += 1
        if name is None or not text.startswith("(", i):
            return None
        end = matching(text, i)
        if end < 0:
            return None
        n, _variadic = count_params(text[i + 1:end - 1])
        return name, n or 0, i + 1, end - 1

    def calls(self, where, built):
        """[(called name, arguments)] of the call expression at a position, then of the calls
        nested in its arguments; [] when the position cannot be read."""
        text, i = self.at(where, built)
        outer = self._call_at(text, i) if text is not None else None
        if outer is None:
            return []
        found = [outer[:2]]
        for m in IDENT.finditer(text, outer[2], outer[3]):
            inner = self._call_at(text, m.start())
            if inner and inner[:2] not in found:
                found.append(inner[:2])
        return found

    def definition(self, where, name, built):
        """Shape (parameters, variadic, void) of the function defined at a position, or None."""
        text, i = self.at(where, built)
        if text is None or not text.startswith(name, i) or IDENT.match(text, i).group(0) != name:
            return None
        j = i + len(name)
        while j < len(text) and text[j] in " \t\n":
            j += 1
        if not text.startswith("(", j):
            return None
        end = matching(text, j)
        if end < 0:
            return None
        n, variadic = count_params(text[j + 1:end - 1])
        start = max(text.rfind(";", 0, i), text.rfind("}", 0, i), text.rfind("{", 0, i)) + 1
        return (n, variadic, returns_void(text[start:i]))

    def pointer_shapes(self, name):
        """Shapes of every declaration of a function pointer called `name` in the sources."""
        if self._decls is None:
            self._index()
        return self._decls.get(name, [])

    def _index(self):
        decls, typedefs = {}, {}
        texts = [t for t in (self.text(p) for p in sorted(self.files)) if t]
        for text in texts:
            for m in POINTER_DECL.finditer(text):
                start = max(text.rfind(c, 0, m.start()) for c in ";{},(") + 1
                prefix = text[start:m.start()]
                end = matching(text, m.end() - 1)
                if end < 0:
                    continue
                n, variadic = count_params(text[m.end():end - 1])
                shape = (n, variadic, returns_void(prefix))
                if re.search(r"\btypedef\b", prefix):
                    typedefs.setdefault(m.group(1), []).append((shape, False))
                else:
                    decls.setdefault(m.group(1), []).append(shape)
            for m in FUNC_TYPEDEF.finditer(text):  # typedef R name(params): a function type
                end = matching(text, m.end() - 1)
                if end < 0:
                    continue
                n, variadic = count_params(text[m.end():end - 1])
                typedefs.setdefault(m.group(2), []).append(((n, variadic, returns_void(m.group(1))), True))
        for text in texts:  # variables and members declared with those typedefs
            for tname, entries in typedefs.items():
                if tname not in text:
                    continue
                for shape, is_function_type in entries:
                    pat = (r"\b%s\s*\*\s*(?:const\s+)?([A-Za-z_]\w*)" if is_function_type
                           else r"\b%s\s+(?:const\s+)?([A-Za-z_]\w*)\s*(?:\[[^\]]*\]\s*)*[;,)=]") % re.escape(tname)
                    for m in re.finditer(pat, text):
                        decls.setdefault(m.group(1), []).append(shape)
        self._decls = decls


# ---------------------------------------------------------------- the image's functions
class Function:
    def __init__(self, key, name, where, frame, qualifier, obj, known=True):
        self.key, self.name, self.where = key, name, where
        self.frame, self.qualifier, self.obj = frame, qualifier, obj
        self.known = known  # False: no call graph (library, assembly): frame is the allowance
        self.calls = set()
        self.sites = []  # positions ('file:line:col', or '' when unknown) of its indirect calls
        self.built = 0.0  # when its call graph was written: positions in newer sources are not read
        self.site_targets = []  # per distinct site: the candidate targets (a tuple of keys)


class Image:
    def __init__(self, args):
        self.args = args
        self.map = LinkMap(args.map)
        self.map_dir = os.path.dirname(os.path.abspath(args.map))
        self.link_dir = os.path.abspath(args.link_dir or self.map_dir)
        self.build_dir = os.path.abspath(args.build_dir)
        self.notes = []  # what the reader should know
        self.errors = []  # what leaves the bound unknown
        self.funcs = {}
        self.section_func = {}  # (map object, section) -> key
        self.address_taken = set()
        self.asm_edges = []
        self.objects_with_graph = 0
        self.library_objects = []
        self.sources = set()
        self._locals = {}  # .ci path -> (symbol name -> key, edges)
        self._load()

    # -- objects
    def _abs(self, rel):
        """A map path made absolute: from the link directory, else the map's, else the build's."""
        if os.path.isabs(rel):
            return os.path.normpath(rel)
        for base in (self.link_dir, self.map_dir, self.build_dir):
            p = os.path.normpath(os.path.join(base, rel))
            if os.path.exists(p):
                return p
        return os.path.normpath(os.path.join(self.link_dir, rel))

    def _inside(self, path):
        return os.path.commonpath([self.build_dir, os.path.abspath(path)]) == self.build_dir

    @staticmethod
    def _aux(objpath, ext):
        base, dot, _ = objpath.rpartition(".")
        return (base if dot else objpath) + ext

    def _locate(self, obj):
        """The object files of a map object: [] for a library, [None] when not found."""
        m = re.match(r"^(.*)\(([^()]+)\)$", obj)
        if not m:
            path = self._abs(obj)
            return [path] if self._inside(path) or os.path.exists(self._aux(path, ".ci")) else []
        archive, member = self._abs(m.group(1)), m.group(2)
        if not self._inside(archive):
            return []
        stem = re.sub(r"^lib|\.a$", "", os.path.basename(archive))
        found = []
        for top in (os.path.join(os.path.dirname(archive), "CMakeFiles", stem + ".dir"), self.build_dir):
            for dirpath, _dirs, files in os.walk(top):
                if (member in files or self._aux(member, ".ci") in files) and \
                        (top != self.build_dir or (stem + ".dir") in dirpath.split(os.sep)):
                    found.append(os.path.join(dirpath, member))
            if found:
                break
        return found or [None]

    def _load(self):
        graphs = []
        for obj in sorted(self.map.kept):
            paths = self._locate(obj)
            if not paths:
                self.library_objects.append(obj)
                continue
            if len(paths) > 1:
                self.notes.append("%s: %d objects of that name in the build; all are counted" % (obj, len(paths)))
            for path in paths:
                ci = self._aux(path, ".ci") if path else None
                if ci is None or not os.path.exists(ci):
                    if path and re.search(r"\.[sS]\.(obj|o)$", path):
                        self.notes.append("%s: assembly, no call graph: its functions count as library code" % obj)
                        self.library_objects.append(obj)
                        continue
                    self.errors.append("no call graph (.ci) for %s (%s)" % (obj, ci or "object not found"))
                    continue
                elf = None
                if path and os.path.exists(path) and os.path.getmtime(ci) < os.path.getmtime(path) - STALE_SECONDS:
                    self.errors.append("the call graph %s is older than its object: left from an earlier build "
                                       "(is -fcallgraph-info=su still in the flags?)" % ci)
                    continue
                if path and os.path.exists(path):
                    try:
                        elf = ElfObject(path)
                    except (ValueError, OSError, struct.error, IndexError) as e:
                        self.notes.append("%s: relocations not read (%s)" % (path, e))
                graphs.append((obj, path, ci, elf))
        for obj, path, ci, elf in graphs:
            self._load_graph(obj, path, ci, elf)
        for obj, _path, ci, elf in graphs:
            self._load_edges(obj, ci, elf)
        called = set()
        for fn in self.funcs.values():
            called |= fn.calls
        self.orphans = sorted(k for k, fn in self.funcs.items()
                              if fn.known and k not in called and k not in self.address_taken
                              and not is_handler(fn.name) and fn.name not in ("Reset_Handler", "main"))
        self.targets = sorted((self.address_taken | set(self.orphans)) & set(self.funcs))

    def _load_graph(self, obj, path, ci, elf):
        source, nodes, edges = read_ci(ci)
        su_path = self._aux(path or ci, ".su")
        su = read_su(su_path) if os.path.exists(su_path) else {}
        self.objects_with_graph += 1
        prefix = (source + ":") if source else None
        elf_sections = {}
        if elf is not None:
            for shndx, fl in elf.funcs.items():
                for _s, _e, name, _g in fl:
                    elf_sections.setdefault(name, elf.sections[shndx])
        local = {}
        for title, (label, where, frame, qual) in nodes.items():
            is_static = prefix is not None and title.startswith(prefix)
            sym = title[len(prefix):] if is_static else title
            # Linked?  The map lists its section as kept or as discarded; else it counts.
            section = elf_sections.get(sym)
            state = None
            for sec in [section] if section else [p + sym for p in TEXT_PREFIXES]:
                state = self.map.state(obj, sec)
                if state:
                    section = sec
                    break
            if state is None and not is_static and self.map.symbols.get(sym, ("",))[0] == obj:
                state, section = "kept", self.map.symbols[sym][1]
            if state == "dropped":
                continue
            if state is None:
                self.notes.append("%s in %s: the map does not say whether it was kept: counted" % (sym, obj))
            if where in su and frame not in su[where]:  # both come from the same figure in GCC
                self.notes.append("%s: .ci says %d bytes, .su %s: the larger counts" % (title, frame, sorted(su[where])))
                frame = max([frame] + list(su[where]))
            local[sym] = title
            if title in self.funcs:  # the same global twice (weak and strong): the worse one
                old = self.funcs[title]
                self.notes.append("%s defined in %s and %s: the larger frame counts" % (title, old.obj, obj))
                old.frame = max(old.frame, frame)
                continue
            self.funcs[title] = Function(title, sym if is_static else label, where, frame, qual, obj)
            self.funcs[title].built = os.path.getmtime(ci)
            if section:
                self.section_func[(obj, section)] = title
            if where:
                src = where.rsplit(":", 2)[0]
                if not os.path.isabs(src):
                    src = os.path.join(self.args.source_root or os.getcwd(), src)
                self.sources.add(os.path.normpath(src))
        if elf is not None:
            self._check_object(obj, ci, elf, nodes, local)
        self._locals[ci] = (local, edges)

    def _check_object(self, obj, ci, elf, nodes, local):
        """Functions of the object that its call graph lacks: a stale .ci, or assembly."""
        known = set((shndx, start) for shndx, fl in elf.funcs.items() for start, _e, n, _g in fl if n in local)
        missing = []
        for shndx, fl in sorted(elf.funcs.items()):
            for start, _e, name, glob in fl:
                if name in local or (shndx, start) in known:  # described, or an alias of one
                    continue
                if self.map.state(obj, elf.sections[shndx]) != "dropped":
                    missing.append((name, glob))
        if missing and not nodes:
            self.errors.append("the call graph %s describes none of the %d functions of its object: stale "
                               "(a failed compile?), rebuild the object" % (ci, len(missing)))
            return
        for name, glob in missing:
            key = name if glob else "%s:%s" % (obj, name)
            self.notes.append("%s in %s: not in the call graph (assembly?): counted as library code" % (name, obj))
            self.funcs[key] = Function(key, name, obj, self.args.library_allowance, "allowance", obj, known=False)
            local[name] = key

    def _unknown(self, name):
        """The node of a function with no call graph (created on first use)."""
        if name not in self.funcs:
            where = self.map.symbols[name][0] if name in self.map.symbols else ""
            allowance = self.args.small_allowance if SMALL_LIBRARY.match(name) else self.args.library_allowance
            fn = Function(name, name, where, allowance, "allowance", where, known=False)
            if name in CALLBACK_LIBRARY:
                fn.sites.append("")
            self.funcs[name] = fn
        return name

    def _library_text(self, name):
        sym = self.map.symbols.get(name)
        return sym is not None and sym[0] in self.library_objects and sym[1].startswith(".text")

    def _load_edges(self, obj, ci, elf):
        local, edges = self._locals[ci]
        for src, dst, loc in edges:
            if src not in self.funcs or self.funcs[src].obj != obj:
                continue  # a function the linker dropped
            if dst == INDIRECT:
                self.funcs[src].sites.append(loc)
            else:
                self.funcs[src].calls.add(local.get(dst) or (dst if dst in self.funcs else self._unknown(dst)))
        if elf is None:
            return
        for shndx, offset, rtype, symi in elf.relocs:
            if rtype in IGNORED_RELOCS or not elf.alloc[shndx] or symi >= len(elf.symbols):
                continue
            secname = elf.sections[shndx]
            if secname.startswith(".ARM.ex") or self.map.state(obj, secname) == "dropped":
                continue
            sname, kind, sshndx = elf.symbols[symi]
            is_call = rtype in CALL_RELOCS
            if kind == 3 and 0 < sshndx < len(elf.sections):  # a section: the functions in it
                targets = [local.get(n, n) for _s, _e, n, _g in elf.funcs.get(sshndx, ())]
            elif kind == 2 and sshndx != 0:  # a function of this object
                targets = [local.get(sname, sname)]
            elif sshndx == 0 and sname:  # defined elsewhere
                if sname in self.funcs:
                    targets = [sname]
                elif is_call or self._library_text(sname):
                    targets = [self._unknown(sname)]
                else:
                    continue  # data
            else:
                continue
            targets = [t for t in targets if t in self.funcs]
            if not targets:
                continue
            if is_call:
                caller = elf.function_at(shndx, offset)
                ckey = local.get(caller, caller) if caller else None
                if ckey not in self.funcs:
                    continue
                for t in targets:
                    if t not in self.funcs[ckey].calls:
                        self.funcs[ckey].calls.add(t)
                        self.asm_edges.append((ckey, t))
            elif secname not in VECTOR_SECTIONS:
                self.address_taken.update(targets)

    # -- indirect call sites
    def narrow_sites(self, sources, enabled=True):
        """Each indirect call site's candidate targets; returns the sites as the report lists them:
        (function, position, called name, arguments, how, candidates)."""
        shapes = {}
        for t in self.targets:
            fn = self.funcs[t]
            shapes[t] = sources.definition(fn.where, fn.name.split(".")[0], fn.built) if fn.known else None
        every = tuple(self.targets)
        listed = []
        for fn in self.funcs.values():
            fn.site_targets = []
            for loc in sorted(set(fn.sites)):
                calls = sources.calls(loc, fn.built) if enabled and loc else []
                how, cands = "unread", every
                name, nargs = calls[0] if calls else (None, None)
                # The call there, if through a name declared as a function pointer; else the
                # pointer calls nested in its arguments (GCC may give an inner call the outer
                # call's position); else (a macro, say) the site keeps every target.
                pointer_calls = [c for c in calls if sources.pointer_shapes(c[0])]
                if calls and calls[0] in pointer_calls:
                    pointer_calls = pointer_calls[:1]
                if pointer_calls:
                    found = set()
                    for called, n in pointer_calls:
                        arity = (n, False, None)
                        decls = [d for d in sources.pointer_shapes(called) if shape_compatible(d, arity)] or [arity]
                        found.update(t for t in every if shapes[t] is None
                                     or any(shape_compatible(d, shapes[t]) for d in decls))
                    how = ("type" if calls[0] in pointer_calls else "nested") if found else "no-target"
                    cands = tuple(t for t in every if t in found)
                    if how == "nested":
                        name, nargs = "/".join(c[0] for c in pointer_calls), pointer_calls[0][1]
                elif calls:
                    how = "not-a-pointer"
                fn.site_targets.append(cands)
                listed.append((fn.key, loc, name, nargs, how, cands))
        return listed

    # -- handlers
    def function_for(self, name):
        """The function a vector name runs (itself, or the function it is an alias of)."""
        if name in self.funcs and self.funcs[name].known:
            return name
        if name in self.map.symbols:
            obj, section, _addr = self.map.symbols[name]
            return self.section_func.get((obj, section))
        return None

    def handlers(self):
        names = set(n for n in self.map.symbols if is_handler(n))
        names |= set(fn.name for fn in self.funcs.values() if fn.known and is_handler(fn.name) and fn.key == fn.name)
        return {n: self.function_for(n) for n in sorted(names) if self.function_for(n)}


# ---------------------------------------------------------------- priorities
ENABLE = re.compile(r"\btse_nvic_enable\s*\(\s*IRQ_(\w+)\s*,\s*([^()]+?)\s*\)")
DEFINE = re.compile(r"^\s*#\s*define\s+(\w+)\s+\(?\s*(0x[0-9a-fA-F]+|\d+)[uUlL]*\s*\)?\s*(?:/[*/].*)?$", re.M)


def read_priorities(sources, headers):
    """({handler name: {level}}, notes) from tse_nvic_enable(IRQ_X, PRIO) in the sources."""
    common = {}
    for h in headers:
        with open(h, errors="replace") as f:
            common.update((m.group(1), int(m.group(2), 0)) for m in DEFINE.finditer(f.read()))
    levels, notes = {}, []
    for src in sorted(sources):
        if not os.path.exists(src):
            continue
        with open(src, errors="replace") as f:
            text = f.read()
        defs = dict(common)
        defs.update((m.group(1), int(m.group(2), 0)) for m in DEFINE.finditer(text))
        for m in ENABLE.finditer(text):
            handler, expr = m.group(1) + "_IRQHandler", m.group(2).strip()
            lm = re.match(r"^(0x[0-9a-fA-F]+|\d+)[uUlL]*$", expr)
            if lm:
                level = int(lm.group(1), 0)
            elif expr in defs:
                level = defs[expr]
            else:
                notes.append("%s: priority '%s' of %s not understood" % (src, expr, handler))
                continue
            levels.setdefault(handler, set()).add(level)
        if re.search(r"\bSHPR\b", blank_source(text)):
            notes.append("%s writes SHPR: system handler priorities other than the reset value are not read" % src)
    return levels, notes


# ---------------------------------------------------------------- depths
def unbounded_frame(fn):
    qual = fn.qualifier.split(",")
    return "dynamic" in qual and "bounded" not in qual


class Depths:
    """Deepest chains.  Direct calls form a DAG unless there is recursion (reported); an indirect
    call goes to the deepest of its site's candidates that is not already on the chain."""

    def __init__(self, image, site_targets):
        self.funcs = image.funcs
        self.site_targets = site_targets  # key -> [tuple of candidate keys per site]
        self.cycles = self._cycles()
        self.in_cycle = set(k for c in self.cycles for k in c)
        # Functions from which an indirect call can be reached by direct calls.
        self.reaches_ind = set(k for k in self.funcs if self.site_targets.get(k))
        changed = True
        while changed:
            changed = False
            for k, fn in self.funcs.items():
                if k not in self.reaches_ind and any(c in self.reaches_ind for c in fn.calls):
                    self.reaches_ind.add(k)
                    changed = True
        targets = set(t for sets in site_targets.values() for s in sets for t in s)
        self.nest = targets & self.reaches_ind  # the targets whose repetition on a chain is tracked
        self.memo = {}
        self.states = 0
        self.too_large = False

    def _cycles(self):
        """Strongly connected components of the direct call graph with a cycle (Tarjan)."""
        index, low, onstack, stack, out = {}, {}, set(), [], []
        for root in sorted(self.funcs):
            if root in index:
                continue
            work = [(root, iter(sorted(self.funcs[root].calls)))]
            index[root] = low[root] = len(index)
            stack.append(root)
            onstack.add(root)
            while work:
                node, it = work[-1]
                advanced = False
                for nxt in it:
                    if nxt not in self.funcs:
                        continue
                    if nxt not in index:
                        index[nxt] = low[nxt] = len(index)
                        stack.append(nxt)
                        onstack.add(nxt)
                        work.append((nxt, iter(sorted(self.funcs[nxt].calls))))
                        advanced = True
                        break
                    if nxt in onstack:
                        low[node] = min(low[node], index[nxt])
                if advanced:
                    continue
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    comp = []
                    while True:
                        k = stack.pop()
                        onstack.discard(k)
                        comp.append(k)
                        if k == node:
                            break
                    if len(comp) > 1 or node in self.funcs[node].calls:
                        out.append(sorted(comp))
        return out

    def cycle_path(self, comp):
        """A call cycle through the members of a strongly connected component."""
        members, start = set(comp), comp[0]
        prev, todo = {start: None}, [start]
        while todo:
            k = todo.pop(0)
            for c in sorted(self.funcs[k].calls):
                if c == start:
                    path = [k]
                    while prev[path[-1]] is not None:
                        path.append(prev[path[-1]])
                    return list(reversed(path)) + [start]
                if c in members and c not in prev:
                    prev[c] = k
                    todo.append(c)
        return comp

    def _enter(self, key, on_chain):
        return on_chain | {key} if key in self.nest else on_chain

    def depth(self, key, on_chain=frozenset()):
        """(bytes, chain [(key, via an indirect call)], bounded) of the deepest chain from key."""
        if key not in self.reaches_ind:
            on_chain = frozenset()
        memo_key = (key, on_chain)
        if memo_key in self.memo:
            return self.memo[memo_key]
        self.states += 1
        if self.states > MAX_STATES:
            self.too_large = True
            return (0, [(key, False)], False)
        fn = self.funcs[key]
        self.memo[memo_key] = (fn.frame, [(key, False)], False)  # provisional: cuts a recursion
        bounded = key not in self.in_cycle and not unbounded_frame(fn)
        best, best_chain = 0, []
        for c in sorted(fn.calls):
            d, chain, b = self.depth(c, self._enter(c, on_chain))
            bounded = bounded and b
            if d > best:
                best, best_chain = d, chain
        for cands in self.site_targets.get(key, ()):
            for t in cands:
                if t in on_chain or t == key:
                    continue
                d, chain, b = self.depth(t, self._enter(t, on_chain))
                bounded = bounded and b
                if d > best:
                    best, best_chain = d, [(t, True)] + chain[1:]
        result = (fn.frame + best, [(key, False)] + best_chain, bounded)
        self.memo[memo_key] = result
        return result

    def root(self, key):
        return self.depth(key, self._enter(key, frozenset()))

    def reachable(self, key):
        """Every function some chain from key can reach."""
        seen, todo = set(), [key]
        while todo:
            k = todo.pop()
            if k in seen:
                continue
            seen.add(k)
            todo.extend(self.funcs[k].calls)
            for cands in self.site_targets.get(k, ()):
                todo.extend(cands)
        return seen


def levels_of(img, handlers, prio):
    """{level: {vector name: function}}: every handler name at its level(s); a handler function
    placed nowhere gets a level of its own."""
    levels, placed = {}, set()
    for name, key in handlers.items():
        if name in CORE_LEVELS:
            lv = {CORE_LEVELS[name]}
        elif name in CORE_RESET_PRIORITY_0:
            lv = {0}
        else:
            lv = prio.get(name, ())
        for level in lv:
            levels.setdefault(level, {})[name] = key
            placed.add(key)
    unplaced = sorted(set((n, k) for n, k in handlers.items() if k not in placed and n == img.funcs[k].name))
    for i, (name, key) in enumerate(unplaced):
        levels.setdefault("own-%d" % (i + 1), {})[name] = key
    return levels


def worst_case(dep, thread_key, handlers, levels):
    """(thread result, {handler function: result}, level rows, total, bounded)."""
    thread = dep.root(thread_key) if thread_key else None
    per_handler = {}
    for key in sorted(set(handlers.values())):
        per_handler[key] = dep.root(key)
    rows = []
    total = thread[0] if thread else 0
    bounded = thread[2] if thread else True
    for lv in sorted(levels, key=lambda v: (1, 0, v) if isinstance(v, str) else (0, -v, "")):
        members = levels[lv]
        key = max(members.values(), key=lambda k: (per_handler[k][0], k))
        d = per_handler[key]
        rows.append((lv, key, sorted(n for n, k in members.items() if k == key), d[0], sorted(members)))
        total += d[0] + EXCEPTION_FRAME + ALIGN_PAD
        bounded = bounded and d[2]
    return thread, per_handler, rows, total, bounded and not dep.too_large


# ---------------------------------------------------------------- report
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--map", required=True, help="the image's link map")
    ap.add_argument("--build-dir", required=True, help="the build directory holding the objects")
    ap.add_argument("--elf", help="the image (names the report: IMAGE.stack.txt beside it)")
    ap.add_argument("--report", help="where to write the report (default: beside the .elf or the map)")
    ap.add_argument("--link-dir", help="directory the map's relative paths start from (default: the map's)")
    ap.add_argument("--ldscript", help="linker script to read _stack_size from if the map lacks it")
    ap.add_argument("--stack-size", type=lambda s: int(s, 0), help="override the reserved stack (bytes)")
    ap.add_argument("--source-root", help="the sources: pointer declarations, relative paths, report paths")
    ap.add_argument("--prio-header", action="append", default=[], help="header with the PRIO_* macros")
    ap.add_argument("--library-allowance", type=int, default=LIBRARY_ALLOWANCE,
                    help="bytes counted for a function with no call graph (default %(default)s)")
    ap.add_argument("--small-allowance", type=int, default=SMALL_ALLOWANCE,
                    help="the same for mem*/str* routines and __aeabi helpers (default %(default)s)")
    ap.add_argument("--no-type-match", action="store_true",
                    help="every indirect call may reach every target (no narrowing by pointer type)")
    ap.add_argument("--json", help="write the figures as JSON too")
    ap.add_argument("--quiet", action="store_true", help="print only the summary lines")
    args = ap.parse_args(argv)
    if args.source_root:
        args.source_root = os.path.abspath(args.source_root)

    image_name = re.sub(r"\.(elf|map)$", "", os.path.basename(args.elf or args.map))
    report_path = args.report or os.path.join(os.path.dirname(os.path.abspath(args.elf or args.map)),
                                              image_name + ".stack.txt")
    img = Image(args)
    stack_size = args.stack_size or img.map.stack_size
    if stack_size is None and args.ldscript:
        stack_size = stack_size_from_script(args.ldscript)
    sources = Sources(args.source_root, img.sources)
    sites = img.narrow_sites(sources, enabled=not args.no_type_match)
    dep = Depths(img, {k: fn.site_targets for k, fn in img.funcs.items() if fn.site_targets})
    every = tuple(img.targets)
    dep_all = Depths(img, {k: [every] * len(fn.site_targets) for k, fn in img.funcs.items() if fn.site_targets})

    thread_key = img.function_for("Reset_Handler") or ("main" if "main" in img.funcs else None)
    handlers = img.handlers()
    prio, prio_notes = read_priorities(img.sources, args.prio_header)
    levels = levels_of(img, handlers, prio)
    thread, per_handler, rows, total, bounded = worst_case(dep, thread_key, handlers, levels)
    _t, _h, _r, total_all, bounded_all = worst_case(dep_all, thread_key, handlers, levels)
    dyn = [fn for fn in img.funcs.values() if fn.known and unbounded_frame(fn)]
    ok = bounded and stack_size is not None and total <= stack_size and not img.errors
    per_level = EXCEPTION_FRAME + ALIGN_PAD

    def name(k):
        return img.funcs[k].name

    def describe(k):
        fn = img.funcs[k]
        if not fn.known:
            return "%s (no call graph: %s)" % (fn.name, os.path.basename(fn.obj) if fn.obj else "not in the map")
        where = fn.where
        if args.source_root and where.startswith(args.source_root + "/"):
            where = where[len(args.source_root) + 1:]
        return "%s (%s)" % (fn.name, where)

    def chain_lines(chain):
        return ["      %6d  %s%s" % (img.funcs[k].frame, "-> (indirect) " if via else "", describe(k))
                for k, via in chain]

    def fmt(r):
        return "%d bytes%s" % (r[0], "" if r[2] else " (UNBOUNDED)")

    lines = []
    out = lines.append
    out("Stack report of %s (cmake/stack_report.py)" % image_name)
    out("  map %s" % os.path.abspath(args.map))
    out("  %d objects linked with a call graph, %d without (library code)" % (img.objects_with_graph,
                                                                              len(img.library_objects)))
    out("")
    out("Own frames, largest 15 (bytes):")
    own = sorted((fn for fn in img.funcs.values() if fn.known), key=lambda f: (-f.frame, f.key))
    for fn in own[:15]:
        out("  %6d  %s%s" % (fn.frame, describe(fn.key), "" if fn.qualifier == "static" else "  [%s]" % fn.qualifier))
    out("")
    if thread:
        out("Deepest chain from the thread root %s: %s" % (name(thread_key), fmt(thread)))
        lines.extend(chain_lines(thread[1]))
    else:
        out("No thread root (Reset_Handler or main) in the image.")
    out("")
    out("Deepest chain of each exception handler (its own code, without the exception frame):")
    for key in sorted(per_handler, key=lambda k: (-per_handler[k][0], k)):
        aliases = sorted(n for n, k in handlers.items() if k == key and n != name(key))
        out("  %s%s: %s" % (name(key), " (also " + ", ".join(aliases) + ")" if aliases else "", fmt(per_handler[key])))
        lines.extend(chain_lines(per_handler[key][1]))
    out("")
    out("Worst case of the stack: the thread's deepest chain, then per priority level the deepest handler")
    out("and %d bytes of exception frame (%d with the FPU context + %d of alignment):" % (per_level, EXCEPTION_FRAME,
                                                                                         ALIGN_PAD))
    if thread:
        out("  %6d  thread: %s" % (thread[0], " > ".join(name(k) for k, _v in thread[1][:4])
                                    + (" > ..." if len(thread[1]) > 4 else "")))
    for lv, key, names, d, allnames in rows:
        out("  %6d  level %s: %s%s (%d + %d); at this level: %s" % (
            d + per_level, lv, name(key), "" if name(key) in names else " as " + "/".join(names), d, per_level,
            ", ".join(allnames)))
    out("  %6d  total (%d levels of exception nesting), of %s reserved (_stack_size)%s" % (
        total, len(rows), stack_size if stack_size is not None else "?",
        ": %d bytes to spare" % (stack_size - total) if stack_size is not None and total <= stack_size else ""))
    if not args.no_type_match:
        out("  (%d%s with every address-taken function possible at every indirect call)"
            % (total_all, "" if bounded_all else ", unbounded"))
    out("")

    by_how = {}
    for s in sites:
        by_how[s[4]] = by_how.get(s[4], 0) + 1
    out("Indirect calls: %d sites in %d functions.  Possible targets: the %d functions whose address is taken"
        % (len(sites), len(set(s[0] for s in sites)), len(img.targets)))
    out("outside the vector table%s; a chain never enters one twice:" % (
        ", or that nothing in the call graph calls" if img.orphans else ""))
    for i in range(0, len(img.targets), 6):
        out("  " + ", ".join(name(t) for t in img.targets[i:i + 6]))
    if img.orphans:
        out("  of which nothing in the call graph calls: " + ", ".join(name(k) for k in img.orphans))
    out("Narrowed per site to the targets of the shape the pointer's declaration allows (parameters; void or")
    out("not): %d sites (%d of them through a call nested in the arguments at the position GCC gives, %d"
        % (by_how.get("type", 0) + by_how.get("nested", 0) + by_how.get("no-target", 0), by_how.get("nested", 0),
           by_how.get("no-target", 0)))
    out("with no target of that shape in the image); not narrowed: %d whose position cannot be read (none, or"
        % by_how.get("unread", 0))
    out("the source changed after the build), %d where no function pointer is called at that position."
        % by_how.get("not-a-pointer", 0))
    groups = {}
    for key, loc, called, nargs, how, cands in sites:
        groups.setdefault((called or "?", nargs, how, cands), []).append(name(key))
    for (called, nargs, how, cands), callers in sorted(groups.items(), key=lambda g: (g[0][0], str(g[0][1]))):
        out("  %s(%s args) [%s] in %s" % (called, "?" if nargs is None else nargs, how,
                                           ", ".join(sorted(set(callers)))))
        out("      -> " + (", ".join(name(t) for t in cands) if len(cands) < len(img.targets) else "every target"))
    if img.asm_edges:
        out("Calls found in the relocations only (assembly, invisible to the call graph), counted:")
        for a, b in sorted(img.asm_edges):
            out("  %s -> %s" % (name(a), name(b)))
    roots = ([thread_key] if thread else []) + list(per_handler)
    reached = set()
    for r in roots:
        reached |= dep.reachable(r)
    unknown = sorted(k for k in reached if not img.funcs[k].known)
    out("Functions without a call graph reached (library code; counted as %d bytes each, %d for the mem*/str*"
        % (args.library_allowance, args.small_allowance))
    out("routines and __aeabi helpers; calling nothing of the firmware%s):"
        % ("; qsort/bsearch may make an indirect call" if any(k in CALLBACK_LIBRARY for k in unknown) else ""))
    for i in range(0, len(unknown), 6):
        out("  " + ", ".join("%s %d" % (k, img.funcs[k].frame) for k in unknown[i:i + 6]))
    if not unknown:
        out("  none")
    out("Recursion: %s" % ("none" if not dep.cycles else "%d cycles; the depth through them is unbounded:"
                                                           % len(dep.cycles)))
    for c in dep.cycles:
        out("  " + " -> ".join(name(k) for k in dep.cycle_path(c)))
    for fn in dyn:
        out("Dynamic frame (alloca or a variable-length array), unbounded: %s" % describe(fn.key))
    out("Priorities: tse_nvic_enable() in the linked sources%s; NMI -2, HardFault -1, the other system"
        % ((" with " + ", ".join(os.path.basename(h) for h in args.prio_header)) if args.prio_header else ""))
    out("handlers 0 (reset value); a handler without a known priority has a level of its own.")
    for n in prio_notes:
        out("  " + n)
    if img.notes:
        out("Notes:")
        for n in img.notes:
            out("  " + n)
    out("Not seen: inline assembly that moves sp; calls through a pointer cast to an incompatible type;")
    out("library code calling back into the firmware (other than qsort/bsearch); library frames beyond the")
    out("allowance; priorities set other than by tse_nvic_enable; code placed without a section in the map.")
    if img.errors or dep.too_large:
        out("Errors:")
        for e in img.errors:
            out("  " + e)
        if dep.too_large:
            out("  too many combinations of indirect calls (> %d states): no bound" % MAX_STATES)

    summary = []
    if thread:
        summary.append("stack %s: thread %d (%s), %s" % (
            image_name, thread[0], " > ".join(name(k) for k, _v in thread[1][:3]) + " ...",
            ", ".join("level %s %d (%s)" % (lv, d, name(k)) for lv, k, _n, d, _a in rows)))
    summary.append("stack %s: worst case %s%d of %s bytes reserved%s" % (
        image_name, "" if bounded else "unbounded, at least ", total, stack_size, "" if ok else " -- FAIL"))
    if not ok:
        why = []
        if img.errors:
            hint = ""
            if any(e.startswith("no call graph") for e in img.errors):
                hint = ("; if this build directory was configured before -fstack-usage -fcallgraph-info=su "
                        "came into cmake/arm-none-eabi.cmake, reconfigure it: cmake --preset stm32f4 --fresh")
            why.append("%d call graph problems (%s)%s" % (len(img.errors), img.errors[0], hint))
        if dep.cycles:
            why.append("recursion, no bound: " + "; ".join(" -> ".join(name(k) for k in dep.cycle_path(c))
                                                         for c in dep.cycles))
        if dyn:
            why.append("unbounded dynamic frame in " + ", ".join(fn.name for fn in dyn))
        if dep.too_large:
            why.append("indirect-call search too large")
        if stack_size is None:
            why.append("_stack_size not found in the map (give --ldscript or --stack-size)")
        elif bounded and total > stack_size:
            why.append("the worst case exceeds the reserved stack by %d bytes" % (total - stack_size))
        summary.append("stack %s: FAIL: %s (report: %s)" % (image_name, "; ".join(why), report_path))
    lines.append("")
    lines.extend(summary)

    with open(report_path, "w") as f:
        f.write("\n".join(lines) + "\n")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({
                "image": image_name, "stack_size": stack_size, "total": total, "ok": ok, "bounded": bounded,
                "total_every_target": total_all,
                "thread": {"bytes": thread[0], "chain": [name(k) for k, _ in thread[1]]} if thread else None,
                "handlers": {name(k): {"bytes": r[0], "bounded": r[2], "chain": [name(c) for c, _ in r[1]]}
                             for k, r in per_handler.items()},
                "levels": [{"level": lv, "handler": names[0], "function": name(k), "bytes": d}
                           for lv, k, names, d, _a in rows],
                "cycles": [[name(k) for k in c] for c in dep.cycles],
                "indirect_targets": [name(t) for t in img.targets],
                "sites": [{"in": name(k), "at": loc, "calls": called, "args": nargs, "how": how,
                           "targets": [name(t) for t in cands]} for k, loc, called, nargs, how, cands in sites],
                "unknown_reached": unknown,
                "asm_edges": [[name(a), name(b)] for a, b in img.asm_edges],
                "errors": img.errors,
            }, f, indent=1)
    print("\n".join(summary if args.quiet else lines))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
