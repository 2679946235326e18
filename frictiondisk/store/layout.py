"""The names of what a campaign directory DIR holds (frictiondisk.engine.runner describes
the layout): one place for the writers, the status report and the figures that read them."""

from __future__ import annotations

CAMPAIGN_FILE = "campaign.yaml"
RECORD_FILE = "campaign.record.json"  # sha256 and canonical form of campaign.yaml
STATUS_FILE = "status.json"
RESULTS_FILE = "results.nc"
RUNS_FILE = "runs.nc"
TRAJECTORY_FILE = "trajectory.nc"  # a trajectory campaign's recorded run
MANIFEST_FILE = "campaigns.json"  # a folder of several campaigns: their names, in order
LOCK_FILE = "lock"
JOURNAL_DIR = "journal"
# Every name the driver reads or writes in DIR: none may be a symbolic link.
DIR_NAMES = (
    LOCK_FILE,
    MANIFEST_FILE,
    CAMPAIGN_FILE,
    RECORD_FILE,
    STATUS_FILE,
    RESULTS_FILE,
    RUNS_FILE,
    TRAJECTORY_FILE,
    JOURNAL_DIR,
    "journal/computed.log",
    "journal/corrupt",
)
