#!/usr/bin/env python3
"""Tests of tools/mpi-replay.py against closed forms: equal tile costs, where the makespan
follows by hand from the counter's batches, static blocks and the ring allgather.
Run by CTest (tools.mpi_replay)."""

import importlib.util
import math
import os
import unittest

_spec = importlib.util.spec_from_file_location(
    "mpi_replay", os.path.join(os.path.dirname(os.path.abspath(__file__)), "mpi-replay.py"))
replay = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(replay)

C = 0.01  # seconds per tile


class EqualTileCosts(unittest.TestCase):
    def test_static_blocks_take_their_share_in_rounds_of_threads(self):
        # 64 tiles on 4 ranks of 2 threads: 16 tiles a rank, 8 rounds of its two threads.
        self.assertAlmostEqual(replay.static_makespan([C] * 64, 4, 2), 8 * C)
        # 10 tiles on 3 ranks: blocks of 3, 3 and 4; one thread each.
        self.assertAlmostEqual(replay.static_makespan([C] * 10, 3, 1), 4 * C)

    def test_one_rank_pays_a_round_trip_per_batch(self):
        # Batches of half what is left (at least one): 32, 16, 8, 4, 2, 1, 1, then the empty
        # answer that ends the wave: 8 requests, each a latency and a service time.
        latency, service = 1e-4, 1e-5
        self.assertAlmostEqual(replay.dynamic_makespan([C] * 64, 1, 1, latency, service),
                               64 * C + 8 * (latency + service))

    def test_free_communication_comes_within_a_tile_of_the_ideal(self):
        for nodes, threads in ((2, 1), (4, 2), (8, 4)):
            ideal = 256 * C / (nodes * threads)
            got = replay.dynamic_makespan([C] * 256, nodes, threads, 0.0, 0.0)
            self.assertGreaterEqual(got, ideal - 1e-12)
            self.assertLessEqual(got, ideal + 2 * C, (nodes, threads))

    def test_the_exchange_is_a_ring_allgather_and_the_collectives(self):
        latency, bandwidth, frame = 3e-5, 1.25e9, 66e6
        self.assertEqual(replay.exchange_seconds(1, frame, latency, bandwidth), 0.0)
        for n in (2, 8, 64):
            expected = (n - 1) * latency + frame * (n - 1) / n / bandwidth + 7 * math.ceil(math.log2(n)) * latency
            self.assertAlmostEqual(replay.exchange_seconds(n, frame, latency, bandwidth), expected)

    def test_a_frame_is_its_waves_and_exchanges(self):
        waves = [[C] * 64] * 3
        p = replay.predict(waves, 4, 2, 1e6, 1e-5, 1e9, 0.0)
        wave_exchange = 3 * 1e-5 + 1e6 * 3 / 4 / 1e9 + 7 * 2 * 1e-5
        wall = 3 * (8 * C + wave_exchange)
        self.assertAlmostEqual(p["static"][0], wall)
        self.assertAlmostEqual(p["static"][1], 3 * 64 * C / (4 * 2 * wall))


class MeasuredCosts(unittest.TestCase):
    def test_waves_come_from_the_tile_runs_in_tile_order(self):
        stats = {"tile_runs": [{"wave": 1, "tile": 1, "cpu_seconds": 4.0}, {"wave": 0, "tile": 1, "cpu_seconds": 2.0},
                               {"wave": 0, "tile": 0, "cpu_seconds": 1.0}, {"wave": 1, "tile": 0, "cpu_seconds": 3.0}]}
        self.assertEqual(replay.wave_costs(stats), [[1.0, 2.0], [3.0, 4.0]])
        self.assertEqual(replay.wave_costs(stats, 2), [[1.0, 2.0, 1.0, 2.0], [3.0, 4.0, 3.0, 4.0]])

    def test_more_samples_add_64_sample_waves_costed_from_the_largest(self):
        stats = {"spp": 4, "waves": [{"samples": [0, 1]}, {"samples": [1, 2]}, {"samples": [2, 4]}]}
        waves = [[1.0], [1.0], [2.0]]
        self.assertEqual(replay.extend_to_spp(waves, stats, 4), waves)
        # 200 spp: 196 more samples, four waves of 64, each 32 times the two-sample wave.
        self.assertEqual(replay.extend_to_spp(waves, stats, 200), waves + [[64.0]] * 4)

    def test_the_counter_beats_static_blocks_when_the_costly_tiles_come_last(self):
        costs = [C] * 90 + [5 * C] * 10  # the adversarial scene: the costly tiles in a corner
        p = replay.predict([costs], 4, 2, 0.0, 1e-5, 1e9, 1e-6)
        # Static: the last rank's block is 15 cheap tiles and the 10 costly ones; on two
        # threads the cheap ones end at 8C and 7C, then the costly ones alternate: 33C; plus
        # the exchange's 3 latencies and 7 collectives of 2.
        self.assertAlmostEqual(p["static"][0], 33 * C + 17 * 1e-5)
        self.assertGreater(p["dynamic"][1], 0.75)
        self.assertGreater(p["dynamic"][1], p["static"][1] + 0.2)


if __name__ == "__main__":
    unittest.main()
