"""Dermis' benchmarks and comparisons (bench/README.md).

Run each script as a module from the repository root, e.g.
`/usr/bin/python3 -m bench.vs_cycles.run --help`; what the scripts share is bench.harness.
"""
