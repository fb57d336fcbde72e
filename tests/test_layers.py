"""The layering of src/: each layer uses only its own and lower layers, no
module is used in a circle or used without being defined, and every
module.mk lists its sources and their dependencies as the `use` statements
say (tests/layers_check.py). The checker itself is tested on small trees
written to a temporary folder."""
import atexit
import os
import shutil
import tempfile

from layers_check import check_layers

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.join(os.path.dirname(HERE), "src")


def test_src_layering():
    problems = check_layers(SRC)
    assert not problems, f"{len(problems)} layering problem(s):\n" + "\n".join(problems)


# A small clean tree: {relative path: text}. module.mk files are derived.
CLEAN = {
    "base/kinds.f90": "module kinds\n  implicit none\n  integer, parameter :: dp = kind(1d0)\nend module kinds\n",
    "base/strings.f90": "module strings\n  use kinds, only: dp\n  use, intrinsic :: iso_fortran_env, only: error_unit\n"
                        "end module strings\n",
    "model/model.f90": "module model\n  use kinds, only: dp ! the reals\n  use strings\nend module model\n",
    "elements/quad.f90": "module quad\n  use :: model\nend module quad\n",
    "elements/quad_impl.f90": "submodule (quad) quad_impl\n  use kinds, only: dp\ncontains\n"
                              "  module procedure area\n  end procedure area\nend submodule quad_impl\n",
    "elements/shim.c": "int shim(void) { return 0; }\n",
    "solver/skyline.f90": "module skyline\n  use kinds, only: dp\n  use iso_c_binding\n"
                          "  use omp_lib\nend module skyline\n",
    "analysis/analysis.f90": "module analysis\n  use quad, only: area\n  use skyline, only: &\n"
                             "     sky_t\nend module analysis\n",
    "cfe2d.f90": "program cfe2d\n  use analysis\nend program cfe2d\n",
}
# The dependency list each object needs in the clean tree.
CLEAN_DEPS = {"kinds": "", "strings": "kinds", "model": "kinds strings", "quad": "model",
              "quad_impl": "kinds quad", "skyline": "kinds", "analysis": "quad skyline"}


def module_mk(files, deps, layer):
    stems = sorted(os.path.splitext(os.path.basename(p))[0] for p in files if p.startswith(layer + "/"))
    out = [f"# Layer: {layer}.", "MODULES += " + " ".join(stems)]
    for stem in stems:
        if stem in deps:
            objs = " ".join(f"$(OBJDIR)/{d}.o" for d in deps[stem].split())
            out.append(f"$(OBJDIR)/{stem}.o: {objs}".rstrip())
    return "\n".join(out) + "\n"


def tree(files=None, deps=None, mk_edit=None):
    """Write a tree under a new temporary folder; return the src path inside it."""
    files = dict(CLEAN if files is None else files)
    deps = dict(CLEAN_DEPS if deps is None else deps)
    top = tempfile.mkdtemp(prefix="layers-")
    atexit.register(shutil.rmtree, top, True)
    src = os.path.join(top, "src")
    layers = {p.split("/")[0] for p in files if "/" in p}
    for rel, text in files.items():
        path = os.path.join(src, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(text)
    for layer in layers:
        text = module_mk(files, deps, layer)
        if mk_edit:
            text = mk_edit(layer, text)
        with open(os.path.join(src, layer, "module.mk"), "w") as f:
            f.write(text)
    return src


def with_files(**changes):
    files = dict(CLEAN)
    files.update({k.replace("__", "/") + ".f90": v for k, v in changes.items()})
    return files


def expect(problems, *fragments, count=None):
    text = "\n".join(problems)
    for frag in fragments:
        assert frag in text, f"{frag!r} not reported; got:\n{text or '(nothing)'}"
    if count is not None:
        assert len(problems) == count, f"expected {count} problem(s), got:\n{text}"


def test_checker_clean_tree_passes():
    problems = check_layers(tree())
    assert problems == [], "\n".join(problems)


def test_checker_upward_use():
    files = with_files(base__strings="module strings\n  use kinds\n  use model, only: x\nend module strings\n")
    problems = check_layers(tree(files, dict(CLEAN_DEPS, strings="kinds model")))
    expect(problems, "src/base/strings.f90:3: use model: layer base (rank 0) uses "
                     "src/model/model.f90 of layer model (rank 1), a higher rank")


def test_checker_equal_rank_cross_use():
    files = with_files(elements__quad="module quad\n  use model\n  use skyline\nend module quad\n")
    problems = check_layers(tree(files, dict(CLEAN_DEPS, quad="model skyline")))
    expect(problems, "src/elements/quad.f90:3: use skyline", "same rank", count=1)


def test_checker_own_layer_and_main_program_allowed():
    # The main program may use any layer; analysis may use itself and lower ones.
    files = with_files(cfe2d="program cfe2d\n  use analysis\n  use kinds\n  use skyline\nend program cfe2d\n")
    assert check_layers(tree(files)) == []


def test_checker_cycle():
    files = with_files(elements__quad="module quad\n  use model\n  use quad_extra\nend module quad\n",
                       elements__quad_extra="module quad_extra\n  use quad\nend module quad_extra\n")
    deps = dict(CLEAN_DEPS, quad="model quad_extra", quad_extra="quad")
    problems = check_layers(tree(files, deps))
    expect(problems, "circular use: quad -> quad_extra -> quad", count=1)


def test_checker_undefined_module():
    files = with_files(model__model="module model\n  use kinds\n  use strings\n  use nowhere_mod\nend module model\n")
    problems = check_layers(tree(files))
    expect(problems, "src/model/model.f90:4: use nowhere_mod: module nowhere_mod is defined nowhere")


def test_checker_intrinsic_ignored_only_when_intrinsic():
    files = with_files(base__kinds="module kinds\n  use, intrinsic :: iso_c_binding, only: c_int\n"
                                   "  use ieee_arithmetic\nend module kinds\n")
    assert check_layers(tree(files)) == []


def test_checker_module_mk_missing_dependency():
    problems = check_layers(tree(deps=dict(CLEAN_DEPS, model="kinds")))
    expect(problems, "src/model/module.mk:3: dependency line of model.o", "missing strings.o", count=1)


def test_checker_module_mk_extra_dependency():
    problems = check_layers(tree(deps=dict(CLEAN_DEPS, analysis="quad skyline model")))
    expect(problems, "src/analysis/module.mk:3:", "not used model.o", count=1)


def test_checker_module_mk_submodule_needs_parent():
    problems = check_layers(tree(deps=dict(CLEAN_DEPS, quad_impl="kinds")))
    expect(problems, "dependency line of quad_impl.o", "missing quad.o", count=1)


def test_checker_module_mk_c_object_has_no_deps():
    problems = check_layers(tree(deps=dict(CLEAN_DEPS, shim="kinds")))
    expect(problems, "dependency line of shim.o", "not used kinds.o", count=1)


def test_checker_source_not_in_modules():
    def drop(layer, text):
        return text.replace("MODULES += kinds strings", "MODULES += kinds") if layer == "base" else text
    problems = check_layers(tree(mk_edit=drop))
    expect(problems, "src/base/strings.f90:1: strings is not listed in MODULES of src/base/module.mk",
           count=1)


def test_checker_missing_dependency_line():
    deps = dict(CLEAN_DEPS)
    del deps["strings"]
    problems = check_layers(tree(deps=deps))
    expect(problems, "no dependency line $(OBJDIR)/strings.o:", count=1)


def test_checker_unknown_folder():
    files = dict(CLEAN)
    files["misc/extra.f90"] = "module extra\nend module extra\n"
    problems = check_layers(tree(files))
    expect(problems, "folder misc is not a known layer")


def test_checker_continued_dependency_line():
    def split(layer, text):
        return text.replace("$(OBJDIR)/quad.o $(OBJDIR)/skyline.o",
                            "$(OBJDIR)/quad.o \\\n  $(OBJDIR)/skyline.o")
    assert check_layers(tree(mk_edit=split)) == []
