# cfe2d - build, run and test. `make help` lists the targets.

FC       ?= gfortran
ifeq ($(FC),f77)
FC       := gfortran
endif
BUILD    ?= build
OPTFLAGS ?= -O2 -march=x86-64 -mtune=generic
DBGFLAGS := -std=f2008 -Wall -Wextra -Wno-compare-reals -Wno-maybe-uninitialized -fcheck=all,no-array-temps \
            -g -fbacktrace -O0
FFLAGS   ?= $(OPTFLAGS)
LIBS     ?= -lcholmod -lumfpack -lamd -lcolamd -lsuitesparseconfig -lmetis -llapack -lopenblas
PYTHON   ?= python3

OBJDIR := $(BUILD)/obj
MODDIR := $(BUILD)/mod

# Program modules in dependency order (see the explicit rules below).
MODULES := kinds messages strings solver_codes skyline sparse_matrix cholmod_binding umfpack_binding \
           metis_binding blas_info linear_solver deck_input model deck_parser materials \
           element_types plane_elements cfe_element element_library \
           ordering contact assembly listing results_gmsh analysis
OBJS := $(MODULES:%=$(OBJDIR)/%.o)

TESTS := test_elements test_skyline test_cfe test_solvers

.PHONY: all debug run check bench deps clean help
all: bin/cfe2d

help:
	@echo "make            build bin/cfe2d (optimised)"
	@echo "make debug      build build-debug/cfe2d with -std=f2008 -Wall -fcheck=all -g -fbacktrace"
	@echo "make run        install what is missing, then run the main example"
	@echo "make check      install what is missing, build, run every test"
	@echo "make bench      solver benchmark (about 1e4, 1e5, 1e6 dofs)"
	@echo "make deps       install compilers, libraries, gmsh and Python packages"

bin/cfe2d: $(OBJS) $(OBJDIR)/cfe2d.o | bin
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)

# The debug build keeps its objects and executable apart: build-debug/cfe2d.
debug:
	$(MAKE) BUILD=build-debug FFLAGS="$(DBGFLAGS)" build-debug/cfe2d

build-debug/cfe2d: $(OBJS) $(OBJDIR)/cfe2d.o
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)

bin $(OBJDIR) $(MODDIR) $(BUILD)/tests:
	mkdir -p $@

$(OBJDIR)/%.o: src/%.f90 | $(OBJDIR) $(MODDIR)
	$(FC) $(FFLAGS) -J$(MODDIR) -c $< -o $@

$(BUILD)/tests/test_report.o: tests/unit/test_report.f90 | $(BUILD)/tests $(MODDIR)
	$(FC) $(FFLAGS) -J$(MODDIR) -c $< -o $@

$(BUILD)/tests/%: tests/unit/%.f90 $(OBJS) $(BUILD)/tests/test_report.o | $(BUILD)/tests
	$(FC) $(FFLAGS) -I$(MODDIR) -o $@ $< $(BUILD)/tests/test_report.o $(OBJS) $(LIBS)

# Explicit module dependencies: an object depends on the objects of the
# modules it uses (their .mod files are written alongside).
$(OBJDIR)/messages.o:
$(OBJDIR)/strings.o: $(OBJDIR)/kinds.o
$(OBJDIR)/deck_input.o: $(OBJDIR)/strings.o $(OBJDIR)/messages.o
$(OBJDIR)/sparse_matrix.o: $(OBJDIR)/kinds.o
$(OBJDIR)/cholmod_binding.o:
$(OBJDIR)/umfpack_binding.o:
$(OBJDIR)/metis_binding.o:
$(OBJDIR)/blas_info.o:
$(OBJDIR)/linear_solver.o: $(OBJDIR)/kinds.o $(OBJDIR)/strings.o $(OBJDIR)/skyline.o $(OBJDIR)/sparse_matrix.o \
                           $(OBJDIR)/cholmod_binding.o $(OBJDIR)/umfpack_binding.o \
                           $(OBJDIR)/metis_binding.o $(OBJDIR)/messages.o $(OBJDIR)/solver_codes.o
$(OBJDIR)/solver_codes.o:
$(OBJDIR)/model.o: $(OBJDIR)/kinds.o $(OBJDIR)/solver_codes.o
$(OBJDIR)/deck_parser.o: $(OBJDIR)/kinds.o $(OBJDIR)/strings.o $(OBJDIR)/deck_input.o $(OBJDIR)/model.o \
                         $(OBJDIR)/solver_codes.o
$(OBJDIR)/materials.o: $(OBJDIR)/kinds.o
$(OBJDIR)/element_types.o: $(OBJDIR)/kinds.o
$(OBJDIR)/plane_elements.o: $(OBJDIR)/element_types.o $(OBJDIR)/materials.o
$(OBJDIR)/cfe_element.o: $(OBJDIR)/element_types.o $(OBJDIR)/plane_elements.o
$(OBJDIR)/element_library.o: $(OBJDIR)/plane_elements.o $(OBJDIR)/cfe_element.o
$(OBJDIR)/skyline.o: $(OBJDIR)/kinds.o
$(OBJDIR)/ordering.o:
$(OBJDIR)/contact.o: $(OBJDIR)/model.o $(OBJDIR)/element_types.o
$(OBJDIR)/assembly.o: $(OBJDIR)/model.o $(OBJDIR)/contact.o $(OBJDIR)/element_library.o \
                      $(OBJDIR)/linear_solver.o $(OBJDIR)/ordering.o
$(OBJDIR)/listing.o: $(OBJDIR)/strings.o $(OBJDIR)/model.o $(OBJDIR)/materials.o $(OBJDIR)/contact.o $(OBJDIR)/messages.o \
                     $(OBJDIR)/solver_codes.o $(OBJDIR)/blas_info.o
$(OBJDIR)/results_gmsh.o: $(OBJDIR)/model.o $(OBJDIR)/materials.o $(OBJDIR)/messages.o
$(OBJDIR)/analysis.o: $(OBJDIR)/strings.o $(OBJDIR)/contact.o $(OBJDIR)/assembly.o $(OBJDIR)/linear_solver.o \
                      $(OBJDIR)/listing.o $(OBJDIR)/results_gmsh.o $(OBJDIR)/messages.o
$(OBJDIR)/cfe2d.o: $(OBJDIR)/deck_parser.o $(OBJDIR)/listing.o $(OBJDIR)/analysis.o $(OBJDIR)/results_gmsh.o

deps:
	bash scripts/install-deps.sh

$(BUILD)/bench: tests/bench/bench.f90 $(OBJS) | $(BUILD)/tests
	$(FC) $(FFLAGS) -I$(MODDIR) -o $@ $< $(OBJS) $(LIBS)

bench: $(BUILD)/bench
	$(PYTHON) scripts/bench.py --exe $(BUILD)/bench

run: deps bin/cfe2d
	$(PYTHON) scripts/run_hertz.py

check: deps
	$(MAKE) bin/cfe2d $(TESTS:%=$(BUILD)/tests/%)
	$(MAKE) debug
	$(PYTHON) tests/run_tests.py --build $(BUILD)

clean:
	rm -rf build build-debug bin
