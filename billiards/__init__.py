"""billiards: an exact pool-break simulator that renders the break to an MP4 film."""

__version__ = "0.1.0"
