"""Dermis against pbrt-v4 on the same files (README.md here): python3 -m bench.pbrt_v4.compare."""
