# Independent oracle for the kriging tests: R's gstat on the same samples, variogram and
# neighbourhood. Usage:
#   Rscript gstat_oracle.R SAMPLES.csv VALUE_COLUMN OUT_DIR MODEL NUGGET PSILL GSTAT_RANGE KAPPA NMAX STRIDE [TREND [EXHAUSTIVE.csv]]
# TREND is the right-hand side of the kriging formula (default 1: ordinary kriging; X + Y: a
# linear drift; U: the sample column U as an external drift, known at the grid nodes from the
# x, y, U columns of EXHAUSTIVE.csv). Samples missing a trend column are dropped.
# MODEL is a gstat model name (Exp, Sph, Gau, Mat); GSTAT_RANGE is in gstat's convention;
# NMAX 0 means global kriging; STRIDE thins the grid. Writes OUT_DIR/grid.csv (x, y, pred, var
# on the 260 x 300 Walker Lake grid, x 1..260, y 1..300, every STRIDE-th node per axis), OUT_DIR/cv.csv (leave-one-out) and
# OUT_DIR/fit.csv (gstat's own fit of MODEL from a generic start) and OUT_DIR/bins.csv.
suppressPackageStartupMessages(library(gstat))
args <- commandArgs(trailingOnly = TRUE)
stopifnot(length(args) >= 10)
trend <- if (length(args) >= 11) args[11] else "1"
form <- as.formula(paste("z ~", trend))
d <- read.csv(args[1])
value <- args[2]
d <- d[!is.na(d[[value]]), ]
d$z <- d[[value]]
if (grepl("U", trend)) d <- d[!is.na(d$U), ]
out <- args[3]
model <- vgm(as.numeric(args[6]), args[4], as.numeric(args[7]), as.numeric(args[5]),
             kappa = as.numeric(args[8]))
nmax <- as.integer(args[9])
if (nmax <= 0) nmax <- Inf
stride <- as.integer(args[10])
grid <- expand.grid(X = seq(1, 260, by = stride), Y = seq(1, 300, by = stride))
if (length(args) >= 12) {
  exh <- read.csv(args[12])
  grid$U <- exh$U[match(paste(grid$X, grid$Y), paste(exh$x, exh$y))]
}
k <- krige(form, ~X + Y, d, newdata = grid, model = model, nmax = nmax, debug.level = 0)
write.csv(data.frame(x = grid$X, y = grid$Y, pred = k$var1.pred, var = k$var1.var),
          file.path(out, "grid.csv"), row.names = FALSE)
cv <- krige.cv(form, ~X + Y, d, model = model, nmax = nmax, verbose = FALSE)
write.csv(data.frame(x = d$X, y = d$Y, observed = cv$observed, pred = cv$var1.pred, var = cv$var1.var),
          file.path(out, "cv.csv"), row.names = FALSE)
v <- variogram(z ~ 1, ~X + Y, data = d)
write.csv(data.frame(np = v$np, dist = v$dist, gamma = v$gamma), file.path(out, "bins.csv"), row.names = FALSE)
start <- vgm(var(d$z), args[4], max(v$dist) / 3, var(d$z) / 10, kappa = as.numeric(args[8]))
f <- fit.variogram(v, start)
write.csv(data.frame(model = as.character(f$model), psill = f$psill, range = f$range),
          file.path(out, "fit.csv"), row.names = FALSE)
