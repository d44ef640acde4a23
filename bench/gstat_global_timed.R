# SPDX-License-Identifier: BSD-3-Clause
# gstat's global kriging at growing sample counts (docs/kriging.md, "At scale"): the first N
# rows of a CSV written by krige_scale.py (x, y, z, v; exponential psill 1, practical range
# 16) kriged onto krige_scale.py's 10^3 grid (--dims 10) with no neighbourhood limit.
# Times krige() alone; prints "samples N nodes M seconds S".
# Usage: Rscript gstat_global_timed.R SAMPLES.csv N
suppressPackageStartupMessages(library(gstat))
a <- commandArgs(trailingOnly = TRUE)
stopifnot(length(a) == 2)
d <- read.csv(a[1])
n <- as.integer(a[2])
stopifnot(n <= nrow(d))
d <- d[seq_len(n), ]
s <- 127 / 9  # krige_scale.py's spacing for a 128^3 field and --dims 10
g <- expand.grid(x = (0:9) * s, y = (0:9) * s, z = (0:9) * s)
m <- vgm(1, "Exp", 16 / 3, 0)  # practical range 16 (docs/kriging.md's convention)
t <- system.time(k <- krige(v ~ 1, ~x + y + z, d, newdata = g, model = m, debug.level = 0))
cat("samples", n, "nodes", nrow(g), "seconds", t[["elapsed"]], "\n")
