# atrito: parallel finite-strain elasto-plastic contact code on PETSc.
#   make          build bin/atrito and the unit-test programs (on all cores unless -j is given)
#   make run      install what is missing, build, run the main job
#   make check    install what is missing, build, run the test suite
#   make bench    assembly throughput benchmark (writes doc/notes/performance-log.md)
#   make doc      the guide as HTML in build/doc (scripts/make_doc.py), its links and figures checked
#   make memcheck the unit tests and short runs under valgrind (scripts/memcheck.sh; make check runs its quick part)

# Nothing here may ask an installed package at parse time: on a fresh machine the Makefile is read
# before scripts/install-deps.sh (the order-only prerequisite $(DEPS_STAMP)) has installed
# anything. Whatever needs PETSc, pkg-config or python3 is a deferred (=) variable, expanded when a
# recipe runs, after the install (tests/test_build.sh checks this).
# every build runs on all cores unless -j is given (nproc is coreutils', not an installed package's),
# or clean is asked for: `make clean all` must clean first, not beside the build
ifeq ($(filter -j%,$(MAKEFLAGS))$(filter clean,$(MAKECMDGOALS)),)
MAKEFLAGS += -j$(shell nproc 2>/dev/null || echo 1)
endif
CC       := mpicc
AR       := gcc-ar
INSTALL_DEPS ?= bash scripts/install-deps.sh
PETSC_CFLAGS = $(shell pkg-config --cflags PETSc 2>/dev/null)
PETSC_LIBS   = $(shell pkg-config --libs PETSc 2>/dev/null)
HDF5_DIR := /usr/lib/x86_64-linux-gnu/hdf5/openmpi
CPPFLAGS = -Iinclude $(PETSC_CFLAGS) -I/usr/include/hdf5/openmpi -I/usr/include/hypre
CFLAGS   ?= -O3 -march=native -flto=auto -g -std=c11 -Wall -Wextra -Wno-unused-parameter -fno-math-errno
LDLIBS   = $(PETSC_LIBS) -L$(HDF5_DIR)/lib -L$(HDF5_DIR) -lhdf5 -ldmumps -lmumps_common -lmetis -lHYPRE -llapack -lm -ldl
# the system Python if it has h5py and matplotlib (installed by install-deps.sh), else python3 on PATH
PYTHON   = $(shell /usr/bin/python3 -c "import h5py, matplotlib" >/dev/null 2>&1 && echo /usr/bin/python3 || echo python3)

LIB_SRC  := $(filter-out src/main.c,$(wildcard src/*.c src/*/*.c))
LIB_OBJ  := $(LIB_SRC:src/%.c=build/%.o)
TEST_SRC := $(wildcard tests/test_*.c)
TEST_BIN := $(TEST_SRC:tests/%.c=bin/%)
DEPS_STAMP := build/.deps-ok
# the test user materials (tests/test_umat.sh): the Fortran UMATs tests/umat_*.f, and the C ones of
# tests/test_umat.c built as a library; only those whose sources exist (names only, no tool asked)
FC       := gfortran
UMAT_SO  := $(patsubst tests/umat_%.f,bin/umat_%.so,$(wildcard tests/umat_*.f)) $(if $(wildcard tests/test_umat.c),bin/umat_ctest.so)

.PHONY: all deps run check bench doc clean sanitize memcheck
all: bin/atrito $(TEST_BIN) $(UMAT_SO)

$(DEPS_STAMP):
	@$(INSTALL_DEPS)
	@mkdir -p build && touch $@

deps: $(DEPS_STAMP)

build/%.o: src/%.c $(wildcard include/*.h src/*/*.h) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) -c $< -o $@

build/lib.a: $(LIB_OBJ)
	rm -f $@ && $(AR) rcs $@ $^

bin/atrito: build/main.o build/lib.a | $(DEPS_STAMP)
	@mkdir -p bin
	$(CC) $(CFLAGS) $^ -o $@ $(LDLIBS)

bin/test_%: tests/test_%.c $(wildcard tests/*.h) build/lib.a $(wildcard include/*.h src/*/*.h) | $(DEPS_STAMP)
	@mkdir -p bin
	$(CC) $(CPPFLAGS) $(CFLAGS) $< build/lib.a -o $@ $(LDLIBS)

bin/umat_%.so: tests/umat_%.f | $(DEPS_STAMP)
	@mkdir -p bin
	$(FC) -O2 -g -shared -fPIC $< -o $@

bin/umat_ctest.so: tests/test_umat.c include/material_umat.h | $(DEPS_STAMP)
	@mkdir -p bin
	$(CC) $(CPPFLAGS) -O2 -g -std=c11 -DUMAT_TEST_LIBRARY -shared -fPIC $< -o $@

# the unit-test programs with AddressSanitizer and UndefinedBehaviorSanitizer (tests/test_memory.sh)
SAN_FLAGS := -O1 -g -std=c11 -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
SAN_OBJ   := $(LIB_SRC:src/%.c=build-san/%.o)
build-san/%.o: src/%.c $(wildcard include/*.h src/*/*.h) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(SAN_FLAGS) -c $< -o $@
bin-san/test_%: tests/test_%.c $(wildcard tests/*.h) $(SAN_OBJ) | $(DEPS_STAMP)
	@mkdir -p bin-san
	$(CC) $(CPPFLAGS) $(SAN_FLAGS) $< $(SAN_OBJ) -o $@ $(LDLIBS)
sanitize: $(TEST_BIN:bin/%=bin-san/%)

# the programs for valgrind's memcheck (scripts/memcheck.sh): uninitialised reads, which the
# sanitizers above do not see. Built without -march=native, whose AVX-512 instructions valgrind
# cannot decode, and at -O1 so that its reports name the lines.
VG_FLAGS := -O1 -g -std=c11 -fno-omit-frame-pointer
VG_OBJ   := $(LIB_SRC:src/%.c=build-vg/%.o)
build-vg/%.o: src/%.c $(wildcard include/*.h src/*/*.h) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(VG_FLAGS) -c $< -o $@
bin-vg/atrito: build-vg/main.o $(VG_OBJ) | $(DEPS_STAMP)
	@mkdir -p bin-vg
	$(CC) $(VG_FLAGS) $^ -o $@ $(LDLIBS)
bin-vg/test_%: tests/test_%.c $(wildcard tests/*.h) $(VG_OBJ) | $(DEPS_STAMP)
	@mkdir -p bin-vg
	$(CC) $(CPPFLAGS) $(VG_FLAGS) $< $(VG_OBJ) -o $@ $(LDLIBS)
memcheck: deps bin-vg/atrito $(TEST_BIN:bin/%=bin-vg/%) $(UMAT_SO)
	@bash scripts/memcheck.sh

run: deps all
	@bash scripts/run-main.sh

check: deps all
	@PYTHON=$(PYTHON) bash tests/run_tests.sh

# the options reference's check asks bin/atrito -help
doc: deps bin/atrito
	@$(PYTHON) scripts/make_doc.py

bench: deps all
	@$(PYTHON) scripts/bench_assembly.py

clean:
	rm -rf build bin build-san bin-san build-vg bin-vg
