"""Reading a campaign directory's netCDF files back for a figure or a report: the whole
Dataset, loaded and closed, or a `CampaignFileError` that names the file and what to do
(a missing, damaged or undrawable file)."""

from __future__ import annotations

from pathlib import Path

from frictiondisk.store.layout import CAMPAIGN_FILE


class CampaignFileError(Exception):
    """A campaign file that is missing, damaged or cannot be drawn: `headline` names the
    file, `details` say what to do."""

    def __init__(self, headline: str, details: list[str]):
        super().__init__("\n  ".join([headline, *details]))
        self.headline = headline
        self.details = details


def load_dataset(path: Path, out_dir: Path):
    """The Dataset in `path` (a file of the campaign directory `out_dir`), fully loaded and
    closed; CampaignFileError naming the file if it is missing or does not load completely
    (e.g. truncated)."""
    import xarray as xr

    remedy = f"rebuild it from the journal: frictiondisk resume {out_dir}"
    if not path.is_file():
        if not (out_dir / CAMPAIGN_FILE).is_file():
            raise CampaignFileError(
                f"{path}: not found",
                [
                    f"{out_dir} is not a campaign directory (no {CAMPAIGN_FILE}); "
                    f"make one with: frictiondisk run CAMPAIGN.yaml -o {out_dir}"
                ],
            )
        raise CampaignFileError(
            f"{path}: not found", [f"the campaign has not finished writing it; {remedy}"]
        )
    try:
        with xr.open_dataset(path, cache=False) as ds:
            return ds.load()
    except Exception as exc:  # any reader error: truncated, corrupted, not netCDF
        detail = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise CampaignFileError(f"{path}: damaged, cannot be read ({detail})", [remedy]) from None
