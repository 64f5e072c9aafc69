//! Result files: CSV tables, `summary.json`, SVG plots.
