"""The one engine: a run's setup, the calendar of next contacts, the batch of runs
advanced together and its log, the stepper's loops (exact, event), the events and the
result. It knows motion models only through `motion_law.MotionLaw` and `result.AnchoredMotion`."""
