"""Campaigns (issue 31): many ROS-free missions drawn from a spec's distributions, run in parallel (local cores or a
Dask cluster), stored one JSON file per run and summarised in a report. docs/campaign.md.

  spec.py      the campaign spec (YAML): load and validate, every error naming its key
  generate.py  run i's scenario and options, a pure function of (spec, i)
  runs.py      one run (mission_rosfree in a subprocess), its outcome class, the per-run store
  execute.py   the local process pool and the Dask cluster, progress
  report.py    success rate and its interval, outcomes, metric distributions, success by variable, worst runs
"""
