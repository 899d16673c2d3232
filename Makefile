# Dermis: two commands do all the set-up (see README.md).
#   make demo   install dependencies, build, render scenes/demo.pbrt to out/demo.{exr,png}
#   make test   install dependencies, build, run the whole test suite through ctest
#   make fuzz   (optional) clang + libFuzzer build in build-fuzz, each fuzz target run for
#               FUZZ_SECONDS seconds (docs/robustness.md)
#   make test-sanitize  (optional) the test suite under AddressSanitizer + UBSan (gcc) in
#               build-asan (docs/robustness.md)
#   make format         clang-format every C++ file in place (.clang-format)
#   make format-check   fail, naming the files, where one is not as clang-format writes it (CI runs it)
BUILD ?= build
JOBS ?= $(shell nproc)
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?= scene_parser ply_reader obj_assimp image_texture point_cloud
SANITIZE_BUILD ?= build-asan
# A compiler launcher for the sanitizer build (e.g. CCACHE=ccache); none by default.
CCACHE ?=
# Left out of the sanitizer run, each for a reason (docs/robustness.md):
#   python.*       CPython is not built with ASan: the extension would need libasan
#                  preloaded into /usr/bin/python3 (LD_PRELOAD) and LeakSanitizer would
#                  judge the interpreter's own allocations alive at exit; the module's C++
#                  is the library that dermis_tests runs under ASan, its bindings are not.
#   bench\.        Python only (the Cycles harness loads); no Dermis code.
#   mpi\.          dermis-mpi (Open MPI) is not built in the sanitizer run.
SANITIZE_EXCLUDE ?= ^(python\.|bench\.|mpi\.)
SANITIZE_ENV = ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS=suppressions=$(CURDIR)/fuzz/lsan.supp:print_suppressions=0

.PHONY: all deps configure build demo test bench fuzz test-sanitize format format-check clean

all: build

deps:
	bash scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: configure
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	mkdir -p out
	./$(BUILD)/dermis render scenes/demo.pbrt -o out/demo.exr

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

bench: build
	./$(BUILD)/dermis_bench

# libFuzzer targets under ASan + UBSan (clang): fuzz/CMakeLists.txt, fuzz/run.sh.
fuzz: deps
	bash scripts/install-fuzz-deps.sh
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g" -DDERMIS_FUZZ=ON
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))
	bash fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# The test suite under AddressSanitizer + UBSan (gcc, -O1 -g), every finding fatal. The
# hostile corpus runs with its CPU limit scaled for ASan (tests/hostile/CMakeLists.txt).
test-sanitize: deps
	cmake -S . -B $(SANITIZE_BUILD) -DDERMIS_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g" \
	  $(if $(CCACHE),-DCMAKE_CXX_COMPILER_LAUNCHER=$(CCACHE) -DCMAKE_C_COMPILER_LAUNCHER=$(CCACHE))
	cmake --build $(SANITIZE_BUILD) -j $(JOBS) --target dermis dermis_tests \
	  $(addsuffix _replay,$(addprefix fuzz_,$(FUZZ_TARGETS)))
	$(SANITIZE_ENV) ctest --test-dir $(SANITIZE_BUILD) --output-on-failure -j $(JOBS) -E '$(SANITIZE_EXCLUDE)'

# Every tracked C++ source and header, as clang-format (Debian's, .clang-format) writes it.
CXX_SOURCES = $(shell git ls-files '*.cpp' '*.h')

format: deps
	clang-format -i $(CXX_SOURCES)

format-check: deps
	@bad=$$(for f in $(CXX_SOURCES); do clang-format --dry-run -Werror "$$f" >/dev/null 2>&1 || echo "$$f"; done); \
	if [ -n "$$bad" ]; then echo "not formatted (make format):"; echo "$$bad"; exit 1; fi

clean:
	rm -rf $(BUILD) out
