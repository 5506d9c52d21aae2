"""The benchmark's sections as its two documents report them: a section's summary for
``results.md`` and its full tables for ``bench.md`` side by side in a module of related
sections, :mod:`.markdown` what they share. ``results.SECTIONS`` is their order in both."""
