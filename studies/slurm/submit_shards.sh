#!/bin/bash
# Submits a sharded study and its merge: the array (shards.sbatch), then the merge
# (merge.sbatch) once every task has succeeded (--dependency=afterok).
#
#   studies/slurm/submit_shards.sh STUDY.toml PARTS_FOLDER OUTPUT.h5 [SHARDS]
#
# Not run by this project's tests (no Slurm here): `bash -n` checks its syntax.
set -euo pipefail

study=${1:?usage: submit_shards.sh STUDY.toml PARTS_FOLDER OUTPUT.h5 [SHARDS]}
parts=${2:?usage: submit_shards.sh STUDY.toml PARTS_FOLDER OUTPUT.h5 [SHARDS]}
output=${3:?usage: submit_shards.sh STUDY.toml PARTS_FOLDER OUTPUT.h5 [SHARDS]}
shards=${4:-16}
here=$(dirname "$0")

array=$(sbatch --parsable --array="1-$shards" --export="ALL,SHARDS=$shards" "$here/shards.sbatch" "$study" "$parts")
array=${array%%;*}  # "jobid;cluster" on a federated cluster
sbatch --dependency="afterok:$array" "$here/merge.sbatch" "$parts" "$output"
