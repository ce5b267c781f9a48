#!/usr/bin/env bash
# A stand-in for `sbatch`: start the job script given as the last argument in the background
# and print a job id, as a scheduler would.
jobscript="${*: -1}"
nohup bash "$jobscript" > "${jobscript}.out" 2>&1 &
echo "$!"
