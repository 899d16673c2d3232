# Dermis: two commands do all the set-up (see README.md).
#   make demo   install dependencies, build, render scenes/demo.pbrt to out/demo.{exr,png}
#   make test   install dependencies, build, run the whole test suite through ctest
BUILD ?= build
JOBS ?= $(shell nproc)

.PHONY: all deps configure build demo test bench clean

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

clean:
	rm -rf $(BUILD) out
