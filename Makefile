# Dermis: two commands do all the set-up (see README.md).
#   make demo   install dependencies, build, render scenes/demo.pbrt to out/demo.{exr,png}
#   make test   install dependencies, build, run the whole test suite through ctest
#   make fuzz   (optional) clang + libFuzzer build in build-fuzz, each fuzz target run for
#               FUZZ_SECONDS seconds (docs/robustness.md)
BUILD ?= build
JOBS ?= $(shell nproc)
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?= scene_parser ply_reader obj_assimp image_texture point_cloud

.PHONY: all deps configure build demo test bench fuzz clean

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

clean:
	rm -rf $(BUILD) out
