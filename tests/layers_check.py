#!/usr/bin/env python3
"""Checks the layering of the Fortran sources under a source root (src/).

Each folder src/<layer>/ has a rank; a file may use modules of its own layer
or of a layer of lower rank, never of a higher rank or of another layer of
the same rank. The main program (files directly in src/) sits on top. The
check also reports circular use, modules used but defined nowhere, sources
missing from their folder's MODULES list and dependency lines of module.mk
that do not match the `use` statements.

    check_layers(src_root) -> list of "file:line: message" strings
    python3 tests/layers_check.py [SRC]      prints them; exit 1 if any
"""
import os
import re
import sys

# Lowest first; layers of equal rank must not use one another.
LAYER_RANKS = {"base": 0, "model": 1, "input": 2, "elements": 2, "solver": 2,
               "contact": 3, "analysis": 4, "output": 5}
MAIN_LAYER, MAIN_RANK = "main", 6
INTRINSIC_MODULES = {"iso_c_binding", "iso_fortran_env", "ieee_arithmetic",
                     "ieee_exceptions", "ieee_features", "omp_lib", "omp_lib_kinds",
                     "openacc"}
FORTRAN_EXTS = (".f90", ".F90", ".f", ".F", ".f95", ".f03", ".f08")
C_EXTS = (".c",)

_USE = re.compile(r"^\s*use\b\s*(?:,\s*(?P<nature>intrinsic|non_intrinsic)\s*)?(?:::)?\s*"
                  r"(?P<name>[a-z_]\w*)", re.I)
_MODULE = re.compile(r"^\s*module\s+(?P<name>[a-z_]\w*)\s*$", re.I)
_SUBMODULE = re.compile(r"^\s*submodule\s*\(\s*(?P<parent>[a-z_]\w*)\s*(?::\s*[a-z_]\w*\s*)?\)"
                        r"\s*(?P<name>[a-z_]\w*)\s*$", re.I)
_NOT_A_MODULE = {"procedure", "function", "subroutine", "pure", "elemental",
                 "recursive", "impure"}


class SourceFile:
    """One source file: its layer, the modules it defines and its use statements."""

    def __init__(self, path, rel, layer, rank):
        self.path, self.rel, self.layer, self.rank = path, rel, layer, rank
        self.stem, self.ext = os.path.splitext(os.path.basename(path))
        self.defines = {}       # module name -> line
        self.parents = []       # (parent module, line) for each submodule
        self.uses = []          # (module name, line, intrinsic?)

    @property
    def is_c(self):
        return self.ext in C_EXTS


def _strip_comment(line):
    """The line without its trailing `!` comment (quotes respected)."""
    quote = None
    for k, ch in enumerate(line):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
        elif ch == "!":
            return line[:k]
    return line


def _scan(src):
    """Fill src.defines, src.parents and src.uses from the file's text."""
    with open(src.path, errors="replace") as f:
        lines = f.read().splitlines()
    continued = False
    for num, raw in enumerate(lines, 1):
        line = _strip_comment(raw).rstrip()
        was_continued, continued = continued, line.endswith("&")
        if was_continued or not line.strip():
            continue
        # Statements separated by ';' are rare in these sources but legal.
        for stmt in line.rstrip("&").split(";"):
            _scan_statement(src, stmt, num)


def _scan_statement(src, stmt, num):
    m = _USE.match(stmt)
    if m:
        name = m.group("name").lower()
        intrinsic = (m.group("nature") or "").lower() == "intrinsic" or (
            m.group("nature") is None and name in INTRINSIC_MODULES)
        src.uses.append((name, num, intrinsic))
        return
    m = _SUBMODULE.match(stmt)
    if m:
        src.parents.append((m.group("parent").lower(), num))
        return
    m = _MODULE.match(stmt)
    if m and m.group("name").lower() not in _NOT_A_MODULE:
        src.defines.setdefault(m.group("name").lower(), num)


def _collect_sources(root, parent):
    """All source files under root, with their layer, and the problems of the tree itself."""
    sources, problems = [], []
    for entry in sorted(os.listdir(root)):
        path = os.path.join(root, entry)
        rel = os.path.relpath(path, parent)
        if os.path.isdir(path):
            if entry not in LAYER_RANKS:
                problems.append(f"{rel}:0: folder {entry} is not a known layer "
                                f"({', '.join(LAYER_RANKS)})")
                continue
            for name in sorted(os.listdir(path)):
                if name.endswith(FORTRAN_EXTS + C_EXTS):
                    sources.append(SourceFile(os.path.join(path, name), os.path.join(rel, name),
                                              entry, LAYER_RANKS[entry]))
        elif entry.endswith(FORTRAN_EXTS + C_EXTS):
            sources.append(SourceFile(path, rel, MAIN_LAYER, MAIN_RANK))
    return sources, problems


def _definitions(sources):
    """Module name -> defining SourceFile; duplicates reported."""
    owner, problems = {}, []
    for src in sources:
        for name, line in src.defines.items():
            if name in owner:
                problems.append(f"{src.rel}:{line}: module {name} is also defined in "
                                f"{owner[name].rel}:{owner[name].defines[name]}")
            else:
                owner[name] = src
    return owner, problems


def _layer_problems(sources, owner):
    """Uses of undefined modules, of higher layers and of equal-rank other layers."""
    problems = []
    for src in sources:
        for name, line, intrinsic in src.uses:
            if intrinsic:
                continue
            dep = owner.get(name)
            if dep is None:
                problems.append(f"{src.rel}:{line}: use {name}: module {name} is defined nowhere "
                                f"under the source root")
            elif dep.layer != src.layer and dep.rank >= src.rank:
                how = "a higher" if dep.rank > src.rank else "another layer of the same"
                problems.append(f"{src.rel}:{line}: use {name}: layer {src.layer} (rank {src.rank}) "
                                f"uses {dep.rel} of layer {dep.layer} (rank {dep.rank}), {how} rank")
        for parent, line in src.parents:
            dep = owner.get(parent)
            if dep is None:
                problems.append(f"{src.rel}:{line}: submodule of {parent}: module {parent} is "
                                f"defined nowhere under the source root")
            elif dep.layer != src.layer:
                problems.append(f"{src.rel}:{line}: submodule of {parent} ({dep.rel}) lies in "
                                f"folder {src.layer}, not with its parent in {dep.layer}")
    return problems


def _cycle_problems(sources, owner):
    """One message per strongly connected set of modules that use one another."""
    graph, where = {}, {}
    for src in sources:
        for mod in src.defines:
            graph.setdefault(mod, set())
        for name, line, intrinsic in src.uses:
            if intrinsic or name not in owner:
                continue
            # A program or submodule file stands for itself in the graph.
            for mod in src.defines or [src.rel]:
                graph.setdefault(mod, set()).add(name)
                where.setdefault((mod, name), f"{src.rel}:{line}")
    problems = []
    for comp in _strongly_connected(graph):
        if len(comp) == 1 and comp[0] not in graph[comp[0]]:
            continue
        cycle = _a_cycle(graph, sorted(comp))
        first = where[(cycle[0], cycle[1])]
        problems.append(f"{first}: circular use: {' -> '.join(cycle)}")
    return problems


def _strongly_connected(graph):
    """Tarjan's components of a {node: set(nodes)} graph, iteratively."""
    index, low, on_stack, stack, comps, counter = {}, {}, set(), [], [], [0]
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = counter[0]
        counter[0] += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in graph:
                    continue
                if child not in index:
                    index[child] = low[child] = counter[0]
                    counter[0] += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph[child]))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                comp = []
                while True:
                    top = stack.pop()
                    on_stack.discard(top)
                    comp.append(top)
                    if top == node:
                        break
                comps.append(comp)
    return comps


def _a_cycle(graph, comp):
    """A closed path a -> ... -> a through the component, starting at its first member."""
    members, start = set(comp), comp[0]
    paths, seen = [[start]], {start}
    while paths:
        path = paths.pop(0)
        for nxt in sorted(graph[path[-1]]):
            if nxt == start:
                return path + [start]
            if nxt in members and nxt not in seen:
                seen.add(nxt)
                paths.append(path + [nxt])
    return comp + [start]


def _read_module_mk(path):
    """MODULES entries [(name, line)] and {object stem: [(line, [dependency tokens])]}
    of one module.mk (backslash continuations joined)."""
    modules, deps = [], {}
    with open(path, errors="replace") as f:
        raw = f.read().splitlines()
    logical, k = [], 0
    while k < len(raw):
        start, text = k + 1, raw[k]
        while text.endswith("\\") and k + 1 < len(raw):
            k += 1
            text = text[:-1] + " " + raw[k]
        logical.append((start, text.split("#", 1)[0]))
        k += 1
    for num, text in logical:
        m = re.match(r"^\s*MODULES\s*\+?=\s*(.*)$", text)
        if m:
            modules += [(w, num) for w in m.group(1).split()]
            continue
        m = re.match(r"^\s*\$\(OBJDIR\)/(\S+)\.o\s*:(?!=)(.*)$", text)
        if m:
            deps.setdefault(m.group(1), []).append((num, m.group(2).split()))
    return modules, deps


def _makefile_problems(sources, owner, root, parent):
    """MODULES lists and dependency lines of each layer's module.mk against the sources."""
    problems = []
    by_layer = {}
    for src in sources:
        by_layer.setdefault(src.layer, []).append(src)
    for layer in sorted(by_layer):
        if layer == MAIN_LAYER:
            continue
        mk = os.path.join(root, layer, "module.mk")
        mk_rel = os.path.relpath(mk, parent)
        if not os.path.exists(mk):
            problems.append(f"{mk_rel}:0: missing: folder {layer} has sources but no module.mk")
            continue
        modules, deps = _read_module_mk(mk)
        listed = {name for name, _ in modules}
        stems = {src.stem for src in by_layer[layer]}
        for src in by_layer[layer]:
            if src.stem not in listed:
                problems.append(f"{src.rel}:1: {src.stem} is not listed in MODULES of {mk_rel}")
            problems += _dependency_line_problems(src, owner, deps.get(src.stem, []), mk_rel)
        for name, num in modules:
            if name not in stems:
                problems.append(f"{mk_rel}:{num}: MODULES lists {name} but {layer}/ has no "
                                f"source {name}.f90 or {name}.c")
        for stem, entries in sorted(deps.items()):
            if stem not in stems:
                problems.append(f"{mk_rel}:{entries[0][0]}: dependency line for {stem}.o but "
                                f"{layer}/ has no source {stem}.f90 or {stem}.c")
    return problems


def _dependency_line_problems(src, owner, entries, mk_rel):
    """One object's `$(OBJDIR)/x.o: ...` lines against the modules its source uses."""
    if src.is_c:
        want = set()
    else:
        want = {owner[name].stem + ".o" for name, _, intrinsic in src.uses
                if not intrinsic and name in owner and owner[name] is not src}
        want |= {owner[p].stem + ".o" for p, _ in src.parents if p in owner and owner[p] is not src}
    if not entries:
        if want or not src.is_c:
            return [f"{mk_rel}:0: no dependency line $(OBJDIR)/{src.stem}.o: for {src.rel} "
                    f"(it needs: {' '.join(sorted(want)) or 'nothing'})"]
        return []
    problems = []
    if len(entries) > 1:
        problems.append(f"{mk_rel}:{entries[1][0]}: second dependency line for {src.stem}.o "
                        f"(first at line {entries[0][0]})")
    num, tokens = entries[0]
    have, bad = set(), []
    for tok in tokens:
        m = re.match(r"^\$\(OBJDIR\)/(\S+\.o)$", tok)
        (have.add(m.group(1)) if m else bad.append(tok))
    missing, extra = sorted(want - have), sorted(have - want)
    if missing or extra or bad:
        parts = []
        if missing:
            parts.append("missing " + " ".join(missing))
        if extra:
            parts.append("not used " + " ".join(extra))
        if bad:
            parts.append("not an $(OBJDIR)/x.o object " + " ".join(bad))
        problems.append(f"{mk_rel}:{num}: dependency line of {src.stem}.o does not match the use "
                        f"statements of {src.rel}: {'; '.join(parts)}")
    return problems


def check_layers(src_root):
    """Purpose: every layering problem of the sources under src_root.
    Arguments: src_root, the folder holding one sub-folder per layer (src/).
    Returns a list of "file:line: message" strings (paths relative to the
    folder above src_root); empty when the tree is clean."""
    root = os.path.abspath(src_root)
    parent = os.path.dirname(root)
    sources, problems = _collect_sources(root, parent)
    for src in sources:
        if not src.is_c:
            _scan(src)
    owner, dup = _definitions(sources)
    problems += dup
    problems += _layer_problems(sources, owner)
    problems += _cycle_problems(sources, owner)
    problems += _makefile_problems(sources, owner, root, parent)
    return problems


def main(argv):
    root = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__))), "src")
    problems = check_layers(root)
    for p in problems:
        print(p)
    print(f"layers: {len(problems)} problem(s) under {root}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
