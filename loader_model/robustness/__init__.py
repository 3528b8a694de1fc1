"""Robustness study (issue 14): ride control over sampled plants, roads, speeds and loads."""
