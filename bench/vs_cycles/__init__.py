"""Dermis against Blender's Cycles at equal error (README.md here): python3 -m bench.vs_cycles.run."""
