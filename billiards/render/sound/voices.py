"""The break's sound track, synthesized from its contact events.

Each ball-ball contact is a click and each cushion contact a thump, placed at the
event's time to within a sample. numpy and the standard library only, never GL.

The voices are physically inspired, not measured:

- A click is the Hertz contact of two phenolic balls. The contact lasts
  tc = 0.41 ms * v^-1/5 (v in m/s), so faster hits are shorter pulses with more
  high-frequency energy: each partial is weighted by the spectrum of a pulse that
  long, which is what makes a hard hit brighter. The click itself is that pulse's
  derivative (a bipolar pressure spike, no DC), a few damped partials of 3-8 kHz
  that ring for 1-2 ms, and a 0.4 ms noise burst.
- A thump is a ball sinking into the rubber nose for several milliseconds: the
  longer pulse only excites the rail's low modes (~140 Hz and ~330 Hz, ringing for
  tens of milliseconds) plus low-passed noise. A jaw (a cushion's rounded end at a
  pocket; an event of kind "cushion" with its pocket named) is the same rubber.
- A pocket's thud is a dropped ball landing in the pocket's leather: softer still
  (a ~25 ms contact), so only a dull low body (~70 Hz and ~170 Hz) and heavily
  smoothed noise, heard POCKET_FALL_TIME after the ball crossed into the pocket (the
  fall), at the speed it lands with (its speed across and POCKET_LANDING_SPEED down).
- The cue's strike (an event of kind "strike", at the cue's speed) is the leather tip
  pressed into the ball for about a millisecond (Alciatore's high-speed films, TP
  A-30's discussion): a "tock" lower and duller than a click, the ball's ring damped
  by the tip, with a short woody ring of the shaft under it.

Loudness: every voice is normalized to its own peak, then scaled by
(v / 3 m/s)^0.7 (a gentle law so slow contacts stay audible), a cushion thump by
0.6 of that and a pocket's thud by 0.8. Each event gets its own small variation (pitch +-3 %, decay +-10 %,
level +-1 dB, its own noise) from np.random.default_rng((seed, index)), so repeated
hits differ yet the same events and seed always give the same samples. The sum goes
through a soft limiter that leaves everything below 0.7 untouched and keeps the
track inside [-1, 1].

Time: sample k of a track is at film time start + k / sample_rate. An event's film
time is time_map(event.time) (the simulation time itself when time_map is None); its
click is loudest within a fraction of a millisecond after that time.
"""

from __future__ import annotations

import math
import wave
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np
import numpy.typing as npt

from billiards.record.trajectory import Event
from billiards.shell.atomic import atomic_output

FloatArray = npt.NDArray[np.float64]
TimeMap = Callable[[FloatArray], FloatArray]

SAMPLE_RATE = 48_000  # Hz
REFERENCE_SPEED = 3.0  # m/s: the break's cue-ball speed gives a full-level click
LOUDNESS_EXPONENT = 0.7  # level ~ speed^0.7
MAX_SPEED = 12.0  # m/s: faster impacts sound like this one (a gentle clip)
CLICK_LEVEL = 0.4  # peak of a click at the reference speed
THUMP_LEVEL = 0.6 * CLICK_LEVEL  # a cushion is duller and softer than a ball
LIMITER_KNEE = 0.7  # samples below this pass unchanged

# Ball-ball click: Hertz contact time at 1 m/s for two 57 mm phenolic balls.
CLICK_CONTACT_TIME = 4.1e-4  # s
CLICK_PARTIALS = (3300.0, 4850.0, 6400.0, 7900.0)  # Hz
CLICK_DECAYS = (1.8e-3, 1.3e-3, 0.9e-3, 0.7e-3)  # s, e-folding time of each partial
CLICK_ATTACK = 6e-5  # s
CLICK_NOISE_DECAY = 4e-4  # s
CLICK_LENGTH = 0.012  # s of samples computed per click (> 6 decay times)

# Cushion thump: the rubber nose gives a much longer contact.
THUMP_CONTACT_TIME = 6e-3  # s at 1 m/s
THUMP_PARTIALS = (140.0, 330.0)  # Hz, rail modes
THUMP_DECAYS = (0.018, 0.010)  # s
THUMP_LENGTH = 0.15  # s of samples computed per thump

# Pocket thud: a ball dropping onto the pocket's leather, a soft and long contact.
POCKET_LEVEL = 0.8 * CLICK_LEVEL
POCKET_CONTACT_TIME = 0.025  # s at 1 m/s
POCKET_PARTIALS = (70.0, 170.0)  # Hz: the ball and the pocket's cup, heavily damped
POCKET_DECAYS = (0.045, 0.02)  # s
POCKET_LENGTH = 0.3  # s of samples computed per thud
POCKET_FALL_TIME = 0.12  # s from crossing into the pocket to landing (~7 cm down)
POCKET_LANDING_SPEED = 1.2  # m/s down when it lands, sqrt(2 g 7 cm)

# The cue's strike: a ~1 ms tip contact, at the cue's speed.
STRIKE_LEVEL = 0.8 * CLICK_LEVEL
STRIKE_CONTACT_TIME = 1.0e-3  # s at 1 m/s
STRIKE_PARTIALS = (480.0, 1350.0, 2700.0)  # Hz: the shaft, the ball damped by the tip
STRIKE_DECAYS = (0.010, 0.004, 0.0015)  # s
STRIKE_LENGTH = 0.06  # s of samples computed per strike

# Per-event variation (1 sigma-ish uniform half-widths).
PITCH_SPREAD = 0.03
DECAY_SPREAD = 0.10
LEVEL_SPREAD_DB = 1.0


def synthesize(
    events: Sequence[Event],
    duration: float,
    *,
    start: float = 0.0,
    sample_rate: int = SAMPLE_RATE,
    seed: int = 0,
    time_map: TimeMap | None = None,
    stretch: float | Sequence[float] | FloatArray = 1.0,
) -> npt.NDArray[np.float32]:
    """The mono sound track of a list of contact events, float32 in [-1, 1].

    The track covers film time [start, start + duration) in round(duration *
    sample_rate) samples; sample k is at film time start + k / sample_rate.

    time_map maps an array of event (simulation) times to film times, for slow
    motion; None means film time = simulation time. stretch slows the sounds
    themselves by that factor, as a slowed recording would: each click lasts
    `stretch` times longer and is pitched down by the same factor (2 = an octave
    lower). Pass 1 (the default) to keep the sounds natural while time_map slows
    the picture, or, for "sound slowed to match", the local slow-down at each event
    (one value per event, e.g. matched_stretch(time_map, times)). Events whose sound
    falls outside the track are cut off or left out; the index of an event in
    `events` picks its variation, so the same list and seed give the same samples.
    """
    if duration < 0 or not np.isfinite(duration):
        raise ValueError(f"duration = {duration}: expected a finite number >= 0")
    if sample_rate <= 0:
        raise ValueError(f"sample_rate = {sample_rate}: expected a positive whole number")
    length = round(duration * sample_rate)
    track = np.zeros(length, dtype=np.float64)
    if not events or length == 0:
        return track.astype(np.float32)

    # A pocket's thud sounds when the dropped ball lands, a fall after the event.
    sim_times = np.array(
        [event.time + (POCKET_FALL_TIME if event.kind == "pocket" else 0.0) for event in events],
        dtype=np.float64,
    )
    film_times = sim_times if time_map is None else np.asarray(time_map(sim_times), np.float64)
    stretches = np.broadcast_to(np.asarray(stretch, dtype=np.float64), sim_times.shape)
    if film_times.shape != sim_times.shape:
        raise ValueError("time_map must return one film time per event time")
    if not np.all(stretches > 0):
        raise ValueError("stretch must be positive")

    for index, event in enumerate(events):
        speed = float(event.impact_speed)
        if event.kind == "pocket":  # it lands with its speed across and its fall's down
            speed = math.hypot(speed, POCKET_LANDING_SPEED)
        speed = min(speed, MAX_SPEED)
        if not speed > 0:
            continue  # a grazing contact makes no sound
        voice, span, level = _VOICES.get(event.kind, _VOICES["cushion"])
        rng = np.random.default_rng((seed, index))
        variation = _Variation.draw(rng)
        onset = (film_times[index] - start) * sample_rate
        indices, since_contact = _grain_clock(
            onset, span * stretches[index], sample_rate, stretches[index]
        )
        shape = voice(since_contact, speed, variation, rng)
        level *= variation.level
        gain = level * (speed / REFERENCE_SPEED) ** LOUDNESS_EXPONENT / np.max(np.abs(shape))
        inside = (indices >= 0) & (indices < length)
        track[indices[inside]] += gain * shape[inside]
    return soft_limit(track).astype(np.float32)


def matched_stretch(time_map: TimeMap, times: FloatArray, step: float = 1e-3) -> FloatArray:
    """The local slow-down d(film time)/d(simulation time) at each time, for `stretch`."""
    times = np.asarray(times, dtype=np.float64)
    slope = (time_map(times + step) - time_map(times - step)) / (2 * step)
    return np.maximum(np.asarray(slope, dtype=np.float64), 1e-6)


def soft_limit(samples: FloatArray, knee: float = LIMITER_KNEE) -> FloatArray:
    """Identity below the knee, a tanh shoulder above: smooth, odd, and inside [-1, 1]."""
    magnitude = np.abs(samples)
    over = magnitude > knee
    shoulder = knee + (1 - knee) * np.tanh((magnitude[over] - knee) / (1 - knee))
    limited = samples.copy()
    limited[over] = np.sign(samples[over]) * shoulder
    return limited


def write_wav(path: str | Path, samples: npt.ArrayLike, sample_rate: int = SAMPLE_RATE) -> None:
    """Write a mono 16-bit PCM WAV; a temporary file beside it is renamed when complete."""
    target = Path(path)
    pcm = np.round(np.clip(np.asarray(samples, dtype=np.float64), -1.0, 1.0) * 32767.0)
    data = pcm.astype("<i2").tobytes()
    with atomic_output(target, ".wav") as temporary, wave.open(str(temporary), "wb") as wav:
        wav.setnchannels(1)
        wav.setsampwidth(2)
        wav.setframerate(sample_rate)
        wav.writeframes(data)


# --- voices ------------------------------------------------------------------------------


class _Variation:
    """One event's deviation from the nominal voice (drawn from its own generator)."""

    def __init__(self, pitch: float, decay: float, level: float) -> None:
        self.pitch = pitch
        self.decay = decay
        self.level = level

    @classmethod
    def draw(cls, rng: np.random.Generator) -> _Variation:
        pitch, decay, level_db = rng.uniform(-1.0, 1.0, size=3)
        return cls(
            pitch=1.0 + PITCH_SPREAD * pitch,
            decay=1.0 + DECAY_SPREAD * decay,
            level=10.0 ** (LEVEL_SPREAD_DB * level_db / 20.0),
        )


def _contact_time(at_one_metre_per_second: float, speed: float) -> float:
    """Hertz contact duration, ~ v^-1/5."""
    return at_one_metre_per_second * max(speed, 1e-3) ** -0.2


def _pulse_spectrum(frequency: float, contact_time: float) -> float:
    """Smooth magnitude spectrum of a half-sine force pulse (a Gaussian of its rms width)."""
    width = 0.22 * contact_time
    return float(np.exp(-2.0 * (np.pi * width * frequency) ** 2))


def _click(
    u: FloatArray, speed: float, variation: _Variation, rng: np.random.Generator
) -> FloatArray:
    """A ball-ball click at times u (s) after contact; zero before it."""
    contact = _contact_time(CLICK_CONTACT_TIME, speed)
    attack, positive = _attack(u, CLICK_ATTACK)
    # The derivative of the half-sine force: a bipolar spike as long as the contact.
    spike = np.where((u >= 0) & (u < contact), np.cos(np.pi * u / contact), 0.0)
    ring = np.zeros_like(u)
    for frequency, decay in zip(CLICK_PARTIALS, CLICK_DECAYS, strict=True):
        f = frequency * variation.pitch * (1.0 + 0.01 * rng.uniform(-1.0, 1.0))
        envelope = np.exp(-positive / (decay * variation.decay))
        ring += _pulse_spectrum(f, contact) ** 0.5 * envelope * np.sin(2 * np.pi * f * positive)
    brightness = _pulse_spectrum(5000.0, contact) ** 0.5  # ~0.3 slow .. ~0.6 hard
    noise = rng.standard_normal(u.shape) * np.exp(-positive / CLICK_NOISE_DECAY)
    return attack * (0.6 * spike + ring + 0.5 * brightness * noise)


def _thump(
    u: FloatArray, speed: float, variation: _Variation, rng: np.random.Generator
) -> FloatArray:
    """A cushion thump at times u (s) after contact; zero before it."""
    contact = _contact_time(THUMP_CONTACT_TIME, speed)
    attack, positive = _attack(u, 0.25 * contact)
    # A harder hit is a shorter pulse: it reaches the upper rail mode and lets
    # higher-frequency noise through (the noise is smoothed over a fifth of the contact).
    brightness = _pulse_spectrum(THUMP_PARTIALS[1], contact) ** 0.5  # ~0 soft .. ~0.4 hard
    weights = (1.0, 0.1 + 1.5 * brightness)
    body = _partials(positive, THUMP_PARTIALS, THUMP_DECAYS, weights, variation)
    noise = _contact_noise(u, contact, 0.2, rng)
    return attack * body + (1.0 + 2.0 * brightness) * noise


def _attack(u: FloatArray, rise: float) -> tuple[FloatArray, FloatArray]:
    """A contact's onset at times u (s) after it, rising over `rise` s (zero before),
    and the times clipped at 0."""
    positive = np.maximum(u, 0)
    return np.where(u >= 0, -np.expm1(-positive / rise), 0.0), positive


def _partials(
    positive: FloatArray,
    frequencies: Sequence[float],
    decays: Sequence[float],
    weights: Sequence[float],
    variation: _Variation,
) -> FloatArray:
    """Decaying sines at times `positive` (s, from 0), one a partial, pitched and damped
    by the event's variation, each at its weight."""
    body = np.zeros_like(positive)
    for frequency, decay, weight in zip(frequencies, decays, weights, strict=True):
        f = frequency * variation.pitch
        envelope = np.exp(-positive / (decay * variation.decay))
        body += weight * envelope * np.sin(2 * np.pi * f * positive)
    return body


def _contact_noise(
    u: FloatArray, contact: float, smoothing: float, rng: np.random.Generator
) -> FloatArray:
    """White noise smoothed over `smoothing` of the contact time (a longer smoothing lets
    only lower frequencies through), sounding under a half sine over two contact times."""
    step = float(u[1] - u[0]) if len(u) > 1 else 1.0
    kernel = np.hanning(max(3, round(smoothing * contact / step)))
    noise = np.convolve(rng.standard_normal(u.shape), kernel / kernel.sum(), mode="same")
    positive = np.maximum(u, 0)
    return noise * np.where(
        (u >= 0) & (u < 2 * contact), np.sin(np.pi * positive / (2 * contact)), 0.0
    )


def _pocket_thud(
    u: FloatArray, speed: float, variation: _Variation, rng: np.random.Generator
) -> FloatArray:
    """A dropped ball landing in its pocket at times u (s) after landing; zero before."""
    contact = _contact_time(POCKET_CONTACT_TIME, speed)
    attack, positive = _attack(u, 0.3 * contact)
    body = _partials(positive, POCKET_PARTIALS, POCKET_DECAYS, (1.0, 0.35), variation)
    # Noise smoothed over half the contact: only its lowest part comes through.
    noise = _contact_noise(u, contact, 0.5, rng)
    return attack * body + 2.0 * noise


def _strike(
    u: FloatArray, speed: float, variation: _Variation, rng: np.random.Generator
) -> FloatArray:
    """The cue's tip striking the ball at times u (s) after contact; zero before."""
    contact = _contact_time(STRIKE_CONTACT_TIME, speed)
    attack, positive = _attack(u, 0.2 * contact)
    weights = [_pulse_spectrum(f * variation.pitch, contact) ** 0.5 for f in STRIKE_PARTIALS]
    body = _partials(positive, STRIKE_PARTIALS, STRIKE_DECAYS, weights, variation)
    noise = rng.standard_normal(u.shape) * np.exp(-positive / (0.6 * contact))
    return attack * (body + 0.4 * noise)


Voice = Callable[[FloatArray, float, _Variation, np.random.Generator], FloatArray]
# Each kind of event: its voice, the seconds of samples it needs, its level.
_VOICES: dict[str, tuple[Voice, float, float]] = {
    "ball": (_click, CLICK_LENGTH, CLICK_LEVEL),
    "cushion": (_thump, THUMP_LENGTH, THUMP_LEVEL),
    "pocket": (_pocket_thud, POCKET_LENGTH, POCKET_LEVEL),
    "strike": (_strike, STRIKE_LENGTH, STRIKE_LEVEL),
}


def _grain_clock(
    onset: float, span: float, sample_rate: int, stretch: float
) -> tuple[npt.NDArray[np.int64], FloatArray]:
    """Track indices covering `span` seconds from fractional sample `onset`, and the
    voice's own time since contact at each (slowed by `stretch`): sub-sample exact."""
    first = int(np.floor(onset))
    indices = first + np.arange(int(np.ceil(span * sample_rate)) + 2, dtype=np.int64)
    since_contact = (indices - onset) / (sample_rate * stretch)
    return indices, since_contact.astype(np.float64)
