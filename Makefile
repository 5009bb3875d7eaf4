# microcontact - plain Makefile (no autotools).
#
#   make run     install missing Debian packages, build, run cases/default.ini
#   make check   install missing packages, build, unit tests + fast verification suites
#   make verify  all verification suites (writes reports/<suite>/)
#   make bench   benchmark report (reports/bench/)
#   make reports every verification report and the paper-figure gallery reports/index.md
#   make bless   rewrite the regression baselines verify/baselines/ (SUITES="a b" for some)
#   make check-sanitize   unit tests + fast suites under AddressSanitizer and UBSan
#   make fuzz FUZZ_SECONDS=N   libFuzzer targets (clang)
#   make mpi     bin/microcontact-mpi (MPI, FFTW-MPI) and make mpi-check its tests under mpirun
#
# Variants: BUILD=build (default) or any directory; SAN=1 builds with ASan+UBSan.

CC       ?= gcc

# OpenMP threads sleep instead of spinning while they wait (the runs and suites started from
# here): on a machine whose cores other jobs share, spinning threads starved each other, e.g. an
# elastic-plastic mesh of the mesh_convergence suite took 477 s spinning and 19.5 s sleeping
# under the same load (measured). Set OMP_WAIT_POLICY=active on an idle machine to override.
export OMP_WAIT_POLICY ?= passive
BUILD    ?= build
SAN      ?= 0
FUZZ_SECONDS ?= 30

DEB_PACKAGES = pkg-config libfftw3-dev libgsl-dev libinih-dev libjansson-dev check libsubunit-dev \
               gnuplot-nox clang libclang-rt-14-dev libzip-dev libxml2-dev nettle-dev \
               libopenmpi-dev openmpi-bin libfftw3-mpi-dev strace

OPT      ?= -O2
CFLAGS_BASE = -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE $(OPT) -g -fopenmp \
              -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes \
              -Isrc -Iverify -Ibench $(shell pkg-config --cflags libxml-2.0 2>/dev/null)
LIBS     = -linih -ljansson -lgsl -lgslcblas -lfftw3_omp -lfftw3 -lzip -lxml2 -lnettle -lm
TESTLIBS = -lcheck_pic -lsubunit -lrt -lpthread

ifeq ($(SAN),1)
  CFLAGS_BASE += -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
  LDFLAGS_SAN = -fsanitize=address,undefined
endif
CFLAGS  ?=
ALL_CFLAGS = $(CFLAGS_BASE) $(CFLAGS)
LDFLAGS += -fopenmp $(LDFLAGS_SAN)

LIB_SRC   = $(filter-out src/cli/%,$(wildcard src/*/*.c))
CLI_SRC   = $(wildcard src/cli/*.c) $(wildcard verify/*.c) $(wildcard bench/*.c)
TEST_SRC  = $(wildcard tests/*.c)

LIB_OBJ   = $(LIB_SRC:%.c=$(BUILD)/%.o)
CLI_OBJ   = $(CLI_SRC:%.c=$(BUILD)/%.o)
TEST_OBJ  = $(TEST_SRC:%.c=$(BUILD)/%.o)
# the one front-end object the unit tests link (tests/test_thread_default.c): the rest of src/cli/
# needs verify/ and bench/, and its mc_cli_ names may not move to another folder (prefixes.sh)
TEST_CLI_OBJ = $(BUILD)/src/cli/thread_default.o

LIBRARY   = $(BUILD)/libmicrocontact.a
ifeq ($(BUILD),build)
  PROGRAM = bin/microcontact
else
  PROGRAM = $(BUILD)/bin/microcontact
endif
TESTS     = $(BUILD)/tests/run_tests

.PHONY: all deps run check _check verify bench reports check-sanitize fuzz clean bless help sample-x3p \
        mpi mpi-check

# ---- MPI: a second executable, bin/microcontact-mpi (README "Running on a cluster") ----------
# The same sources compiled by mpicc with -DMC_MPI into $(BUILD)/mpi and linked with FFTW-MPI;
# built by `all` when mpicc and fftw3-mpi.h are present (make deps installs them), never in a
# sanitizer build (OpenMPI's own allocations would be reported). The serial build is untouched.
MPICC    ?= mpicc
ifeq ($(SAN),0)
  HAVE_MPI := $(shell command -v $(MPICC) >/dev/null 2>&1 && [ -f /usr/include/fftw3-mpi.h ] && echo 1)
endif
MPI_BUILD    = $(BUILD)/mpi
MPI_LIB_OBJ  = $(LIB_SRC:%.c=$(MPI_BUILD)/%.o)
MPI_CLI_OBJ  = $(CLI_SRC:%.c=$(MPI_BUILD)/%.o)
MPI_PROGRAM  = $(dir $(PROGRAM))microcontact-mpi
MPI_TESTS    = $(MPI_BUILD)/tests/mpi_operator
MPI_EIGEN    = $(MPI_BUILD)/tests/mpi_eigen
NPY_COMPARE  = $(BUILD)/tests/npy_compare
MPI_LIBS     = -lfftw3_mpi $(LIBS)

all: $(LIBRARY) $(PROGRAM) $(if $(HAVE_MPI),$(MPI_PROGRAM))

help:
	@sed -n '2,12p' Makefile

# ---- dependencies: check first (fast when present), install only what is missing -----------
deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "make deps: installing$$missing"; \
	  if [ "$$(id -u)" != 0 ]; then SUDO=sudo; else SUDO=; fi; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $$missing >/dev/null || \
	    { echo "make deps: apt-get failed for:$$missing" >&2; exit 1; }; \
	fi

# ---- build ----------------------------------------------------------------------------------
$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -MMD -MP -c $< -o $@

$(LIBRARY): $(LIB_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@ && ar rcs $@ $^

$(PROGRAM): $(CLI_OBJ) $(LIBRARY)
	@mkdir -p $(dir $@)
	$(CC) $(LDFLAGS) -o $@ $(CLI_OBJ) $(LIBRARY) $(LIBS)

$(BUILD)/tests/suites.inc: $(TEST_SRC)
	@mkdir -p $(dir $@)
	@for f in $(filter tests/test_%.c,$(TEST_SRC)); do \
	  n=$$(basename $$f .c); n=$${n#test_}; [ "$$n" = util ] || echo "SUITE($$n)"; done > $@.tmp && mv $@.tmp $@

$(BUILD)/tests/%.o: tests/%.c $(BUILD)/tests/suites.inc
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -Itests -I$(BUILD)/tests -MMD -MP -c $< -o $@

$(TESTS): $(TEST_OBJ) $(TEST_CLI_OBJ) $(LIBRARY)
	@mkdir -p $(dir $@)
	$(CC) $(LDFLAGS) -o $@ $(TEST_OBJ) $(TEST_CLI_OBJ) $(LIBRARY) $(TESTLIBS) $(LIBS)

$(MPI_BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(MPICC) $(ALL_CFLAGS) -DMC_MPI -MMD -MP -c $< -o $@

$(MPI_PROGRAM): $(MPI_CLI_OBJ) $(MPI_LIB_OBJ)
	@mkdir -p $(dir $@)
	$(MPICC) $(LDFLAGS) -o $@ $(MPI_CLI_OBJ) $(MPI_LIB_OBJ) $(MPI_LIBS)

$(MPI_TESTS): tests/mpi/mpi_operator.c tests/mpi/mpi_check.h $(MPI_LIB_OBJ)
	@mkdir -p $(dir $@)
	$(MPICC) $(ALL_CFLAGS) -DMC_MPI -o $@ $< $(MPI_LIB_OBJ) $(LDFLAGS) $(MPI_LIBS)

$(MPI_EIGEN): tests/mpi/mpi_eigen.c tests/mpi/mpi_check.h $(MPI_LIB_OBJ)
	@mkdir -p $(dir $@)
	$(MPICC) $(ALL_CFLAGS) -DMC_MPI -o $@ $< $(MPI_LIB_OBJ) $(LDFLAGS) $(MPI_LIBS)

$(NPY_COMPARE): tests/mpi/npy_compare.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -o $@ $< -lm

-include $(LIB_OBJ:.o=.d) $(CLI_OBJ:.o=.d) $(TEST_OBJ:.o=.d) $(MPI_LIB_OBJ:.o=.d) $(MPI_CLI_OBJ:.o=.d)

mpi: deps
	@$(MAKE) --no-print-directory $(MPI_PROGRAM)

# the distributed operator against the direct sum and across rank counts, and whole runs under
# mpirun -np 2 and 3 against the serial program (tests/cli/mpi.sh)
mpi-check: $(PROGRAM) $(MPI_PROGRAM) $(MPI_TESTS) $(MPI_EIGEN) $(NPY_COMPARE)
	tests/cli/mpi.sh ./$(PROGRAM) ./$(MPI_PROGRAM) ./$(MPI_TESTS) ./$(NPY_COMPARE) ./$(MPI_EIGEN)

# ---- front doors ----------------------------------------------------------------------------
run: deps
	@$(MAKE) --no-print-directory all
	./$(PROGRAM) run cases/default.ini

check: deps
	@$(MAKE) --no-print-directory _check

_check: $(PROGRAM) $(TESTS)
	tools/check_includes.sh
	tools/prefixes.sh $(BUILD)
	CK_DEFAULT_TIMEOUT=600 ./$(TESTS)
	./$(PROGRAM) verify --fast --baselines verify/baselines --reports $(BUILD)/reports-fast
	tests/cli/bad_input.sh ./$(PROGRAM)
	tests/cli/cases.sh ./$(PROGRAM)
	tests/cli/robustness.sh ./$(PROGRAM)
	tests/cli/surface.sh ./$(PROGRAM)
	$(if $(HAVE_MPI),@$(MAKE) --no-print-directory mpi-check)

verify: deps
	@$(MAKE) --no-print-directory all
	./$(PROGRAM) verify --reports reports

bench: deps
	@$(MAKE) --no-print-directory all
	./$(PROGRAM) bench --reports reports

reports: deps
	@$(MAKE) --no-print-directory all
	./$(PROGRAM) verify --all --reports reports

SUITES ?= --all
bless: deps
	@$(MAKE) --no-print-directory all
	./$(PROGRAM) verify --fast --bless $(SUITES) --reports $(BUILD)/reports-fast
	./$(PROGRAM) verify --bless $(SUITES) --reports reports

# the measured-surface example of cases/measured.ini (see tools/make_sample_x3p.c)
sample-x3p: $(LIBRARY)
	$(CC) $(ALL_CFLAGS) -o $(BUILD)/make_sample_x3p tools/make_sample_x3p.c $(LIBRARY) $(LDFLAGS) $(LIBS)
	SOURCE_DATE_EPOCH=1764000000 $(BUILD)/make_sample_x3p cases/data/ground_sample.x3p

check-sanitize: deps
	@$(MAKE) --no-print-directory BUILD=build/san SAN=1 OPT=-O1 _check

# ---- fuzzing (clang libFuzzer) --------------------------------------------------------------
# Each tests/fuzz/fuzz_<x>.c is linked with only the parser sources (scene.c needs kernel.c for
# mc_combined_modulus). `make fuzz FUZZ_SECONDS=N` runs every target N seconds on its seed corpus
# tests/fuzz/corpus/fuzz_<x>/ (and tests/fuzz/fuzz_<x>.dict if present), keeping what it finds in
# build/fuzz/corpus-fuzz_<x>/; it fails at the first target that crashes, leaks or breaks a
# contract (log build/fuzz/fuzz_<x>.log, crashing input build/fuzz/crashes/). UBSan aborts
# (-fno-sanitize-recover) so that undefined behaviour counts as a crash.
FUZZ_TARGETS = $(patsubst tests/fuzz/%.c,build/fuzz/%,$(wildcard tests/fuzz/fuzz_*.c))
FUZZ_LIB_SRC = src/core/error.c src/core/alloc.c src/core/fileguard.c src/core/dist.c src/case/units.c src/case/keys.c src/case/reader.c src/case/scene.c src/case/datafiles.c src/case/scene_effect.c src/plastic/hardening.c \
               src/kernels/kernel.c src/core/grid.c src/io/npy.c src/io/heightmap.c \
               src/io/file.c src/io/le.c src/io/npy_header.c src/io/surface_file.c src/io/x3p_read.c src/io/x3p_write.c \
               src/io/sdf.c src/io/gsf.c src/io/xyz.c
FUZZ_CFLAGS  = -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -g -O1 -Isrc \
               -Wall -Wextra -Werror -Wno-unknown-pragmas \
               -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
               $(shell pkg-config --cflags libxml-2.0 2>/dev/null)
build/fuzz/%: tests/fuzz/%.c tests/fuzz/fuzz_common.h tests/fuzz/fuzz_surface.h $(FUZZ_LIB_SRC) $(wildcard src/*/*.h)
	@mkdir -p $(dir $@)
	clang $(FUZZ_CFLAGS) $< $(FUZZ_LIB_SRC) -o $@ -linih -lgsl -lgslcblas -lzip -lxml2 -lnettle -lm

fuzz: deps
	@$(MAKE) --no-print-directory $(FUZZ_TARGETS)
	@for t in $(FUZZ_TARGETS); do \
	  name=$$(basename $$t); mkdir -p build/fuzz/corpus-$$name build/fuzz/crashes; \
	  dict=; [ -f tests/fuzz/$$name.dict ] && dict=-dict=tests/fuzz/$$name.dict; \
	  echo "fuzz: $$name for $(FUZZ_SECONDS) s"; \
	  $$t -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 $$dict \
	    -artifact_prefix=build/fuzz/crashes/$$name- build/fuzz/corpus-$$name \
	    tests/fuzz/corpus/$$name > build/fuzz/$$name.log 2>&1; \
	  rc=$$?; grep -E 'stat::number_of_executed_units|ERROR|SUMMARY|contract broken' build/fuzz/$$name.log; \
	  if [ $$rc -ne 0 ]; then echo "fuzz: $$name FAILED (exit $$rc), see build/fuzz/$$name.log" >&2; exit 1; fi; \
	done

clean:
	rm -rf build bin
