"""Facts about the synthesized sound track (billiards.render.sound.voices)."""

from __future__ import annotations

import wave
from pathlib import Path

import numpy as np
import numpy.typing as npt

from billiards.record.trajectory import Event
from billiards.render.sound.voices import matched_stretch, soft_limit, synthesize, write_wav

RATE = 48_000
FRAME = 1 / 30  # s, one video frame at the default 30 fps


def ball(time: float, speed: float = 2.0) -> Event:
    return Event(time, "ball", ("cue", "1"), speed)


def cushion(time: float, speed: float = 2.0) -> Event:
    return Event(time, "cushion", ("1",), speed)


def spectral_centroid(samples: npt.NDArray[np.float32]) -> float:
    power = np.abs(np.fft.rfft(samples.astype(np.float64))) ** 2
    frequencies = np.fft.rfftfreq(len(samples), 1 / RATE)
    return float((power * frequencies).sum() / power.sum())


def loudest_time(samples: npt.NDArray[np.float32], start: float, end: float) -> float:
    first, last = round(start * RATE), round(end * RATE)
    return (first + int(np.argmax(np.abs(samples[first:last])))) / RATE


def test_track_has_one_sample_per_sample_period_of_the_duration() -> None:
    assert len(synthesize([ball(0.1)], 2.5)) == round(2.5 * RATE)
    assert len(synthesize([], 1.0, sample_rate=44_100)) == 44_100


def test_track_is_float32_inside_minus_one_to_one() -> None:
    crowd = [ball(0.2 + 1e-4 * i, speed=10.0) for i in range(50)]
    track = synthesize(crowd, 0.5)
    assert track.dtype == np.float32
    assert np.max(np.abs(track)) < 1.0


def test_loudest_moments_fall_within_a_frame_of_the_ball_contacts() -> None:
    times = [0.15, 0.45, 0.75, 1.05, 1.35]
    events = [ball(t, speed=0.5 + i) for i, t in enumerate(times)]
    events += [cushion(t + 0.15, speed=1.0) for t in times]  # quieter thumps in between
    track = synthesize(sorted(events, key=lambda e: e.time), 1.6)
    for t in times:
        peak = loudest_time(track, t - 0.15, t + 0.15)
        assert abs(peak - t) < FRAME
        assert abs(peak - t) < 0.002  # in fact within two milliseconds


def test_click_sits_at_the_event_time_on_a_track_that_starts_before_zero() -> None:
    track = synthesize([ball(0.25)], 1.0, start=-0.5)
    assert abs(loudest_time(track, 0.0, 1.0) - 0.75) < 0.002


def test_slow_motion_moves_the_click_to_its_film_time_and_lowers_its_pitch() -> None:
    def quarter_speed(t: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        return 4.0 * t

    natural = synthesize([ball(0.1)], 0.6, time_map=quarter_speed)
    times = np.array([0.1])
    slowed = synthesize(
        [ball(0.1)], 0.6, time_map=quarter_speed, stretch=matched_stretch(quarter_speed, times)
    )
    assert abs(loudest_time(natural, 0.0, 0.6) - 0.4) < 0.002
    assert abs(loudest_time(slowed, 0.0, 0.6) - 0.4) < 0.004
    assert spectral_centroid(slowed) < 0.5 * spectral_centroid(natural)


def test_same_events_and_seed_give_identical_samples() -> None:
    events = [ball(0.1), cushion(0.2), ball(0.3, 0.4)]
    assert np.array_equal(synthesize(events, 0.5, seed=7), synthesize(events, 0.5, seed=7))


def test_different_seed_gives_different_samples() -> None:
    events = [ball(0.1), cushion(0.2)]
    assert not np.array_equal(synthesize(events, 0.5, seed=1), synthesize(events, 0.5, seed=2))


def test_repeated_hits_do_not_sound_identical() -> None:
    track = synthesize([ball(0.1), ball(0.3)], 0.5)
    first = track[round(0.1 * RATE) : round(0.12 * RATE)]
    second = track[round(0.3 * RATE) : round(0.32 * RATE)]
    assert not np.allclose(first, second, atol=1e-3)


def test_louder_impact_gives_a_louder_click() -> None:
    peaks = [np.max(np.abs(synthesize([ball(0.1, speed)], 0.3))) for speed in (0.1, 0.5, 2.0)]
    assert peaks[0] < peaks[1] < peaks[2]


def test_harder_click_is_brighter() -> None:
    soft = spectral_centroid(synthesize([ball(0.1, 0.1)], 0.3))
    hard = spectral_centroid(synthesize([ball(0.1, 3.0)], 0.3))
    assert hard > soft


def test_cushion_thump_is_duller_than_a_ball_click() -> None:
    click = spectral_centroid(synthesize([ball(0.1)], 0.3))
    thump = spectral_centroid(synthesize([cushion(0.1)], 0.3))
    assert thump < 0.25 * click
    assert thump < 400.0


def test_cushion_thump_lasts_longer_than_a_ball_click() -> None:
    def ringing(track: npt.NDArray[np.float32]) -> float:
        loud = np.nonzero(np.abs(track) > 0.1 * np.max(np.abs(track)))[0]
        return float(loud[-1] - loud[0]) / RATE

    click = ringing(synthesize([ball(0.1)], 0.3))
    thump = ringing(synthesize([cushion(0.1)], 0.3))
    assert click < 0.006
    assert 0.015 < thump < 0.08


def test_events_outside_the_track_are_cut_off_quietly() -> None:
    track = synthesize([ball(-1.0), ball(5.0), cushion(0.995)], 1.0)
    assert np.max(np.abs(track[: round(0.99 * RATE)])) == 0.0
    assert np.max(np.abs(track)) > 0.0


def test_soft_limiter_leaves_quiet_samples_alone_and_stays_inside_one() -> None:
    samples = np.array([-3.0, -0.5, 0.0, 0.3, 0.69, 0.9, 3.0])
    limited = soft_limit(samples)
    assert np.array_equal(limited[1:5], samples[1:5])
    assert np.all(np.abs(limited) < 1.0)
    assert np.all(np.diff(limited) > 0)
    assert np.max(np.abs(soft_limit(np.array([-1e9, 1e9])))) <= 1.0


def test_wav_read_back_has_the_right_length_and_rate(tmp_path: Path) -> None:
    track = synthesize([ball(0.1), cushion(0.3)], 0.75, sample_rate=44_100)
    path = tmp_path / "track.wav"
    write_wav(path, track, 44_100)
    with wave.open(str(path), "rb") as wav:
        assert wav.getnchannels() == 1
        assert wav.getsampwidth() == 2
        assert wav.getframerate() == 44_100
        assert wav.getnframes() == round(0.75 * 44_100)
        read = np.frombuffer(wav.readframes(wav.getnframes()), dtype="<i2") / 32767.0
    assert np.max(np.abs(read - track)) < 1e-4
    assert [p.name for p in tmp_path.iterdir()] == ["track.wav"]  # no temporary left behind


def pocket(time: float, speed: float = 2.0) -> Event:
    return Event(time, "pocket", ("1",), speed, "foot-left")


def test_a_pocket_thud_is_duller_than_a_cushion_thump() -> None:
    from billiards.render.sound.voices import POCKET_FALL_TIME

    thump = synthesize([cushion(0.05)], 0.5)
    thud = synthesize([pocket(0.05 - POCKET_FALL_TIME)], 0.5)
    assert np.max(np.abs(thud)) > 0.05
    assert spectral_centroid(thud) < 0.7 * spectral_centroid(thump)


def test_a_pocket_thud_sounds_when_the_ball_lands_after_its_fall() -> None:
    from billiards.render.sound.voices import POCKET_FALL_TIME

    track = synthesize([pocket(0.2)], 1.0)
    assert np.max(np.abs(track[: round((0.2 + POCKET_FALL_TIME) * RATE)])) == 0.0
    assert 0.2 + POCKET_FALL_TIME < loudest_time(track, 0.0, 1.0) < 0.2 + POCKET_FALL_TIME + 0.05


def test_a_ball_dropping_without_speed_across_still_lands_with_a_thud() -> None:
    assert np.max(np.abs(synthesize([pocket(0.1, speed=0.0)], 0.6))) > 0.02


def test_a_jaw_hit_is_a_cushion_thump() -> None:
    jaw = Event(0.1, "cushion", ("1",), 2.0, "side-top")
    assert np.array_equal(synthesize([jaw], 0.4, seed=3), synthesize([cushion(0.1)], 0.4, seed=3))
