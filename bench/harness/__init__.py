"""What the benchmark scripts share, one concept per module:

  paths          where the repository, its build and its docs are
  render         running `dermis render` (its command line, its time, its log)
  exr            reading a render: an EXR's channels as NumPy arrays
  progress       a run's progress lines
  docs_page      writing a docs page above its hand-written findings
  provenance     the git commit, the dermis version and the CPU a figure came from
  dermis_module  the `dermis` Python module of the build tree
  study          driving a `dermis study` and putting its results in a page
  pictures       PNGs and strips of images for the pages
"""
