"""The Table 6 experiment of section 5.3 and the reproduction report."""
