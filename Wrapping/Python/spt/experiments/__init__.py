"""The experiments behind ``python3 -m spt demo|bench|figures``, apart from the library: the
demo's race (:mod:`.demo`), the benchmark (:mod:`.bench`), the paper's figures
(:mod:`.figures`, with :mod:`.accuracy` and :mod:`.sampling`), and the plots and tables they
write (:mod:`.plots`, :mod:`.tables`). They use the library (``spt.data``, ``spt.render``,
``spt.metrics``, ...); the library never imports them. They are in the source and build trees
only: an install and the wheel leave them out (``build/bin/spt-python`` runs them).
"""
