# gstat's side of bench/kriging_vs_gstat.py: times krige() alone (not R's start-up or the CSV
# reading) on the Walker Lake 260 x 300 grid and writes what it predicted.
# Usage: Rscript gstat_krige_timed.R SAMPLES.csv VALUE MODEL NUGGET PSILL GSTAT_RANGE NMAX RUNS OUT.csv [TREND]
# TREND: the formula's right-hand side (default 1, ordinary kriging; X + Y: a linear drift).
# NMAX 0 means global kriging. Prints one line per run: "seconds S".
suppressPackageStartupMessages(library(gstat))
args <- commandArgs(trailingOnly = TRUE)
stopifnot(length(args) >= 9)
form <- as.formula(paste("z ~", if (length(args) >= 10) args[10] else "1"))
d <- read.csv(args[1])
d$z <- d[[args[2]]]
d <- d[!is.na(d$z), ]
model <- vgm(as.numeric(args[5]), args[3], as.numeric(args[6]), as.numeric(args[4]))
nmax <- as.integer(args[7])
if (nmax <= 0) nmax <- Inf
grid <- expand.grid(X = 1:260, Y = 1:300)
for (run in seq_len(as.integer(args[8]))) {
  t <- system.time(k <- krige(form, ~X + Y, d, newdata = grid, model = model, nmax = nmax,
                              debug.level = 0))
  cat("seconds", t[["elapsed"]], "\n")
}
write.csv(data.frame(x = grid$X, y = grid$Y, pred = k$var1.pred, var = k$var1.var), args[9],
          row.names = FALSE)
