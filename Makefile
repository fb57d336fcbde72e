# cfe2d - build, run and test. `make help` lists the targets.

FC       ?= gfortran
ifeq ($(FC),f77)
FC       := gfortran
endif
BUILD    ?= build
OPTFLAGS ?= -O2 -march=x86-64 -mtune=generic
DBGFLAGS := -std=f2008 -Wall -Wextra -Wno-compare-reals -Wno-maybe-uninitialized -fcheck=all,no-array-temps \
            -g -fbacktrace -O0
# OpenMP: the element loops run on OMP_NUM_THREADS threads (one if it is
# not set; src/solver/thread_shim.c); libgomp is the runtime CHOLMOD links too.
OMPFLAGS ?= -fopenmp
FFLAGS   ?= $(OPTFLAGS) $(OMPFLAGS)
LIBS     ?= -lcholmod -lumfpack -lamd -lcolamd -lsuitesparseconfig -lmetis -larpack -llapack -lopenblas
PYTHON   ?= python3

# MUMPS over MPI (Debian: libmumps-dev with Open MPI), the solver of
# *SOLVER, TYPE=MUMPS and of `mpirun -np N bin/cfe2d`. Found (its header and
# mpicc): the backend is real and the program links MUMPS and MPI. Not found,
# or MUMPS=no: the same program without it (stubs in mumps_shim.c), where
# TYPE=MUMPS is an error at its card. A stamp file rebuilds the two objects
# that depend on the choice when it changes.
MUMPS    ?= $(shell test -f /usr/include/dmumps_c.h && command -v mpicc >/dev/null 2>&1 && echo yes || echo no)
ifeq ($(MUMPS),yes)
MPI_CFLAGS ?= $(shell mpicc --showme:compile 2>/dev/null || mpicc -compile_info 2>/dev/null | cut -d' ' -f2-)
MPI_LIBS   ?= $(shell mpicc --showme:link 2>/dev/null || echo -lmpi)
MUMPS_LIBS ?= -ldmumps -lmumps_common
LIBS       += $(MUMPS_LIBS) $(MPI_LIBS)
MUMPS_DEFS := -DCFE_HAVE_MUMPS $(MPI_CFLAGS)
endif

OBJDIR := $(BUILD)/obj
MODDIR := $(BUILD)/mod

# The program's source lives in one folder per layer (docs/architecture.md);
# each folder's module.mk lists its modules and their explicit dependencies.
.DEFAULT_GOAL := all
LAYERS  := base model input elements solver contact analysis output
MODULES :=
include $(LAYERS:%=src/%/module.mk)
vpath %.f90 $(LAYERS:%=src/%) src
vpath %.c $(LAYERS:%=src/%)
OBJS := $(MODULES:%=$(OBJDIR)/%.o)

TESTS := test_elements test_skyline test_cfe test_solvers test_numbering test_constraints test_strings test_contact_status test_nonlinear

.PHONY: all debug sanitize nompi run check bench deps clean help fuzz kernels fretting
all: bin/cfe2d

help:
	@echo "make            build bin/cfe2d (optimised)"
	@echo "make debug      build build-debug/cfe2d with -std=f2008 -Wall -fcheck=all -g -fbacktrace"
	@echo "                (every build has -fopenmp: OMP_NUM_THREADS=N runs the element loops on N threads)"
	@echo "make sanitize   build build-asan/cfe2d with -fsanitize=address,undefined"
	@echo "make nompi      build build-nompi/cfe2d without MPI and MUMPS (MUMPS=no), as where they are absent"
	@echo "make run        install what is missing, then run the main example"
	@echo "make fretting   McColl's fretting test, 18 000 cycles with a jump of 100 (docs/fretting.md);"
	@echo "                FRETTING_ARGS=\"--jump 1000\" etc. (scripts/fretting.py --help)"
	@echo "make check      install what is missing, build, run every test"
	@echo "make bench      contact history against one factorisation (flagship meshes, 1e6-dof square);"
	@echo "                BENCH_ARGS=--solvers adds the solver table (about 1e4, 1e5, 1e6 dofs); with MUMPS"
	@echo "                the square also on 1 and 2 MPI ranks; --surfaces 250,1000 the contact-surface table"
	@echo "make deps       install compilers, libraries, gmsh and Python packages"
	@echo "make fuzz       mutate the example and test decks and run both builds on them"
	@echo "make kernels    the contact decks under every OpenBLAS kernel of this CPU and the debug build:"
	@echo "                the same contact decisions (tests/test_kernels.py; also part of make check)"

bin/cfe2d: $(OBJS) $(OBJDIR)/cfe2d.o | bin
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)

# The debug build keeps its objects and executable apart: build-debug/cfe2d.
debug:
	$(MAKE) BUILD=build-debug FFLAGS="$(DBGFLAGS) $(OMPFLAGS)" build-debug/cfe2d

build-debug/cfe2d: $(OBJS) $(OBJDIR)/cfe2d.o
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)

# The build of a machine without MPI or MUMPS (MUMPS=no), apart in build-nompi/.
nompi:
	$(MAKE) BUILD=build-nompi MUMPS=no build-nompi/cfe2d

build-nompi/cfe2d: $(OBJS) $(OBJDIR)/cfe2d.o
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)

# The sanitizer build: address and undefined-behaviour checks, apart in build-asan/.
SANFLAGS := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined
sanitize:
	$(MAKE) BUILD=build-asan FFLAGS="$(SANFLAGS) $(OMPFLAGS)" CFLAGS="$(SANFLAGS)" build-asan/cfe2d

build-asan/cfe2d: $(OBJS) $(OBJDIR)/cfe2d.o
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)

bin $(OBJDIR) $(MODDIR) $(BUILD)/tests:
	mkdir -p $@

$(OBJDIR)/%.o: %.f90 | $(OBJDIR) $(MODDIR)
	$(FC) $(FFLAGS) -J$(MODDIR) -c $< -o $@

# C shims (one per C library whose structs must not be mirrored in Fortran).
CC      ?= cc
CFLAGS  ?= -O2
CINC    := -I/usr/include/suitesparse
$(OBJDIR)/%.o: %.c | $(OBJDIR)
	$(CC) $(CFLAGS) $(CINC) -c $< -o $@
$(OBJDIR)/mumps_shim.o $(OBJDIR)/build_features.o: CINC += $(MUMPS_DEFS)
$(OBJDIR)/mumps_shim.o $(OBJDIR)/build_features.o: $(OBJDIR)/mumps-$(MUMPS).stamp
$(OBJDIR)/mumps-$(MUMPS).stamp: | $(OBJDIR)
	rm -f $(OBJDIR)/mumps-*.stamp
	touch $@

$(BUILD)/tests/test_report.o: tests/unit/test_report.f90 | $(BUILD)/tests $(MODDIR)
	$(FC) $(FFLAGS) -J$(MODDIR) -c $< -o $@

$(BUILD)/tests/%: tests/unit/%.f90 $(OBJS) $(BUILD)/tests/test_report.o | $(BUILD)/tests
	$(FC) $(FFLAGS) -I$(MODDIR) -o $@ $< $(BUILD)/tests/test_report.o $(OBJS) $(LIBS)

$(OBJDIR)/cfe2d.o: $(OBJDIR)/directories.o $(OBJDIR)/deck_parser.o $(OBJDIR)/listing.o $(OBJDIR)/analysis.o $(OBJDIR)/results_gmsh.o \
                   $(OBJDIR)/results_vtu.o $(OBJDIR)/results_frd.o $(OBJDIR)/results_dat.o $(OBJDIR)/results_sta.o $(OBJDIR)/tie_constraints.o

deps:
	bash scripts/install-deps.sh

$(BUILD)/bench: tests/bench/bench.f90 $(OBJS) | $(BUILD)/tests
	$(FC) $(FFLAGS) -I$(MODDIR) -o $@ $< $(OBJS) $(LIBS)

# BENCH_ARGS: e.g. --solvers (also the solver table), --meshes default --repeats 1
BENCH_ARGS ?=
bench: $(BUILD)/bench bin/cfe2d
	$(PYTHON) scripts/bench.py --exe $(BUILD)/bench $(BENCH_ARGS)

# MUMPS is decided when make reads this file, before deps installs it: the
# program is built by a second make, which reads the file after the install
# (a fresh machine's `make run` would otherwise build without MUMPS, and the
# `make check` after it build everything again).
run: deps
	$(MAKE) bin/cfe2d
	$(PYTHON) scripts/run_hertz.py

# McColl's fretting test (issue 33): meshes input/fretting/mccoll.geo, runs
# 18 000 cycles with a cycle jump of 100, plots the worn profiles against the
# measured one into results/fretting/ (docs/fretting.md).
FRETTING_ARGS ?=
fretting: deps
	$(MAKE) bin/cfe2d
	$(PYTHON) scripts/fretting.py $(FRETTING_ARGS)

check: deps
	$(MAKE) bin/cfe2d $(TESTS:%=$(BUILD)/tests/%)
	$(MAKE) debug
	$(MAKE) sanitize
	$(MAKE) nompi
	$(PYTHON) tests/run_tests.py --build $(BUILD)

# Contact decisions independent of the BLAS kernel and of the build (tests/test_kernels.py,
# which `make check` runs with the rest; the debug build is compared too).
kernels: bin/cfe2d
	$(MAKE) debug
	$(PYTHON) tests/run_tests.py --build $(BUILD) -k test_kernels

# Mutation fuzzer over the project's decks (scripts/fuzz.py; `make check` runs a short slice).
FUZZ_ARGS ?=
fuzz: bin/cfe2d
	$(MAKE) debug
	$(PYTHON) scripts/fuzz.py $(FUZZ_ARGS)

clean:
	rm -rf build build-debug build-asan build-nompi bin
