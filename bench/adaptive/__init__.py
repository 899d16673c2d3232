"""Adaptive sampling against uniform sampling at equal time: python3 -m bench.adaptive.run."""
