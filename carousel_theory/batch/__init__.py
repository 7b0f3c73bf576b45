"""Fleets of recordings on Dask: one task per recording (or per axis), one table out.

The modules, from the bottom up:

- :mod:`~carousel_theory.batch.rows` — :class:`~carousel_theory.batch.rows.BatchRow`, one row of the
  result table (one recording and axis), and the table's column order;
- :mod:`~carousel_theory.batch.discovery` — files, directories and globs to a sorted list of recordings,
  and the content hash that keys every result;
- :mod:`~carousel_theory.batch.tasks` — the only module that calls the analyses (Allan variance, noise
  fit, closed loop): recording path + options → rows;
- :mod:`~carousel_theory.batch.store` — the table on disk (Parquet and CSV, written atomically) and
  what a resumed run may reuse;
- :mod:`~carousel_theory.batch.report` — the fleet report (Markdown and plots);
- :mod:`~carousel_theory.batch.cluster` — the Dask side: a local cluster or an existing scheduler,
  submission, time-outs, dead workers, progress.

Only :mod:`~carousel_theory.batch.cluster` imports Dask; the rest works without the ``batch`` extra.
"""
