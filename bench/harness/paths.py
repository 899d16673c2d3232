"""Where the repository, its build and its docs are."""
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DERMIS = os.path.join(ROOT, "build", "dermis")  # the binary the scripts run unless told another
RESULTS = os.path.join(ROOT, "docs", "results")  # the pages the comparisons write
IMAGES = os.path.join(ROOT, "docs", "images")  # their pictures
