#!/bin/sh
# Regenerates every figure of docs/ that `pcrf plot` draws, and the paper comparison
# (docs/paper_comparison.csv and .md) they come with. One command:
#     sh docs/make_figures.sh [PCRF]        (default build/pcrf; or: cmake --build build --target figures)
# Needs ../shared/records (PCRF_RECORDS_DIR overrides). About 2 minutes on 2 cores; the
# studies' cubes go to a scratch folder that is removed at the end.
set -eu
cd "$(dirname "$0")/.."
PCRF=$(realpath "${1:-build/pcrf}")
RECORDS=${PCRF_RECORDS_DIR:-../shared/records}
if [ ! -d "$RECORDS/paper" ]; then
  echo "make_figures: $RECORDS/paper not found: the figures need the PEER records" >&2
  exit 2
fi
# The comparison script needs numpy: the Python pcrf plot uses (PCRF_PYTHON), else python3.
PYTHON=${PCRF_PYTHON:-python3}
"$PYTHON" -c 'import numpy' 2>/dev/null || PYTHON=/usr/bin/python3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
RUN=""
if command -v mpirun >/dev/null 2>&1; then RUN="mpirun --oversubscribe -n 2"; fi
SCRATCH=$(mktemp -d)
trap 'rm -rf "$SCRATCH"' EXIT

study() {  # study FILE.toml NAME: its cube in the scratch folder
  $RUN "$PCRF" study "studies/$1" -o "$SCRATCH/$2.h5" --progress-interval-s 0
}
plot() {
  "$PCRF" plot "$@" --overwrite
}

"$PCRF" run --record "$RECORDS/paper/ER1_MUL279.AT2" --scale 3 --history "$SCRATCH/er1.csv" \
  --history-dt-s 0.001 > /dev/null
plot history "$SCRATCH/er1.csv" -o docs/history.png --title "Basic model, ER1 (Northridge, MUL279) x 3"
study paper_section7.toml section7
plot sweep "$SCRATCH/section7.h5" -w scale=2.5 -o docs/sweep.png \
  --title "One-at-a-time sweeps around the basic model, 13 paper records x 2.5"
plot status "$SCRATCH/section7.h5" -w scale=2.5 -o docs/status.png \
  --title "How each case of the sweeps ended (13 paper records x 2.5)"
study fema_p695_ida.toml ida
plot ida "$SCRATCH/ida.h5" -o docs/ida.png --title "Adaptive IDA, 22 FEMA P-695 far-field records"
plot fragility "$SCRATCH/ida.h5" -o docs/fragility.png \
  --title "Collapse fragility from the adaptive IDA (22 FEMA P-695 records)"
study near_field.toml near_field
plot fragility "$SCRATCH/near_field.h5" --reduce-over incidence_deg --reduce min --reduce median \
  --compare-where incidence_deg=0 -o docs/near_field_fragility.png \
  --title "Six near-fault pairs: fragility at fault-normal (incidence_deg=0) and over orientation"
study risk.toml risk
plot risk "$SCRATCH/risk.h5" --hazard studies/risk_hazard_pga.csv -o docs/risk.png \
  --title "Collapse risk, 44 far-field components, synthetic hazard 2.625e-4 x^-3 /yr"
study sensitivity.toml sensitivity
plot sensitivity "$SCRATCH/sensitivity.h5" -m theta_max_rad -o docs/sensitivity.png \
  --title "Sobol' indices of peak rotation: 8 parameters +-30 %, 13 paper records x 2.5"
"$PYTHON" bench/paper_comparison.py --pcrf "$PCRF" --records "$RECORDS" --out docs
plot table3 docs/paper_comparison.csv -o docs/table3.png
echo "make_figures: docs/history.png sweep.png status.png ida.png fragility.png near_field_fragility.png risk.png sensitivity.png table3.png"
