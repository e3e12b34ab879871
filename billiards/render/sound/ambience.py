"""The film's sound bed under the contacts: the room's tone, and the rumble of rolling
balls, which follows their speeds.

Levels, judged by numbers against the contacts (billiards.render.sound.voices: a click at the
break's 3 m/s peaks at 0.4, -8 dBFS): the room tone is a soft, dark hiss at about
-52 dBFS rms, heard only in the pauses; the rolling rumble is band-limited noise
(about 60-400 Hz, the cloth and the slate under a rolling ball) at about -38 dBFS rms
for one ball rolling at 1 m/s, growing with the balls' speeds (as the root of their
squares' sum), so a spread break murmurs some 25 dB under its clicks and the room
stays under that: contact, rolling, room, each well under the one before, as a
microphone over a table hears them. Numpy only; the same seed gives the same samples.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from billiards.record.trajectory import Trajectory
from billiards.render.film_clock import FilmClock
from billiards.render.sound.voices import SAMPLE_RATE

FloatArray = npt.NDArray[np.float64]

ROOM_LEVEL = 0.0025  # rms, about -52 dBFS
ROOM_CORNER = 1500.0  # Hz: the tone falls off above (pink below, darker above)
RUMBLE_LEVEL = 0.0125  # rms for one ball rolling at 1 m/s, about -38 dBFS
RUMBLE_BAND = (60.0, 400.0)  # Hz
RUMBLE_MOST = 4.0  # m/s: faster rolling sounds like this (the drive is capped)
ON_CLOTH = 1e-6  # m: a ball whose centre is lower than its radius less this has dropped


def shaped_noise(count: int, rng: np.random.Generator, gain: FloatArray) -> FloatArray:
    """`count` samples of noise whose spectrum is `gain` (a function of frequency, as
    an array over np.fft.rfftfreq(count, 1 / SAMPLE_RATE)), scaled to unit rms."""
    if count == 0:
        return np.zeros(0)
    spectrum = np.fft.rfft(rng.standard_normal(count)) * gain
    noise = np.fft.irfft(spectrum, count)
    rms = float(np.sqrt(np.mean(noise * noise)))
    return noise / rms if rms > 0 else noise


def rolling_drive(trajectory: Trajectory) -> FloatArray:
    """(F,) m/s at the trajectory's samples: the root of the sum of the squared speeds
    of the balls rolling on the cloth (a dropped ball is silent), capped."""
    times = trajectory.times
    if len(times) < 2:
        return np.zeros(len(times))
    flat = trajectory.positions[:, :, :2]
    velocity = np.gradient(flat, times, axis=0)
    speed = np.sqrt(np.sum(velocity * velocity, axis=2))  # (F, N)
    on_cloth = trajectory.positions[:, :, 2] >= trajectory.radius - ON_CLOTH
    drive = np.sqrt(np.sum(np.where(on_cloth, speed, 0.0) ** 2, axis=1))
    return np.minimum(drive, RUMBLE_MOST)


def sound_bed(trajectory: Trajectory, clock: FilmClock, seed: int) -> npt.NDArray[np.float32]:
    """The room tone and the rolling rumble over the film (float32 at SAMPLE_RATE, as
    long as billiards.render.sound.soundtrack's track: sample k at clock.start + k / rate)."""
    count = round(clock.duration * SAMPLE_RATE)
    frequency = np.fft.rfftfreq(count, 1.0 / SAMPLE_RATE) if count else np.zeros(0)
    rng = np.random.default_rng((seed, 33))  # its own stream: the contacts' stay as they were
    # The room: pink (1 / sqrt(f) in amplitude) from 20 Hz, rolled off above the corner.
    pink = 1.0 / np.sqrt(np.maximum(frequency, 20.0)) / (1.0 + (frequency / ROOM_CORNER) ** 2)
    room = ROOM_LEVEL * shaped_noise(count, rng, pink)
    # The rumble: band-passed noise, its level following the rolling balls' speeds.
    low, high = RUMBLE_BAND
    band = (frequency / low) ** 2 / (1.0 + (frequency / low) ** 2) / (1.0 + (frequency / high) ** 4)
    rumble = shaped_noise(count, rng, band)
    film_times = clock.start + np.arange(count) / SAMPLE_RATE
    frame_times = clock.start + np.arange(clock.frame_count) / clock.fps
    sim_times = np.interp(film_times, frame_times, clock.sim_times)
    drive = np.interp(sim_times, trajectory.times, rolling_drive(trajectory))
    return (room + RUMBLE_LEVEL * drive * rumble).astype(np.float32)
