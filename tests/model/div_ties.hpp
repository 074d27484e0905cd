// Exact ties of the divider's quotient, shared by tests/model/div_test.cpp, div_slow_test.cpp and
// div_shared_recip_test.cpp. With d = m·2^qb and n = (2q + 1)·m (halved when it needs nb + 1 bits
// and is even; an odd one is drawn again), n / d = (q + ½)·2^−(qb−1) exactly: a tie of the
// quotient's round to nearest even at qb bits; n − 1 and n + 1 are its neighbours. Written from
// that identity, not from the model.
#pragma once

#include <cstdint>
#include <random>

namespace fxr::div_ties {

// `draws` draws of (m, q) from rng (m ∈ [2^(db−1−qb), 2^(db−qb)), q ∈ [2^(qb−1), 2^qb)); for each,
// check(n, d) with n = tie − 1, tie, tie + 1 where n has its msb at bit nb − 1. None when
// db − 1 < qb (no such m).
template <class F>
void for_each_tie(int nb, int db, int qb, int draws, std::mt19937_64& rng, F&& check) {
  if (db - 1 - qb < 0) return;
  for (int i = 0; i < draws; ++i) {
    const uint64_t m = (1ull << (db - 1 - qb)) + rng() % (1ull << (db - 1 - qb));
    const uint64_t q = (1ull << (qb - 1)) + rng() % (1ull << (qb - 1));
    unsigned __int128 a = (unsigned __int128)(2 * q + 1) * m;
    if (a >> nb) {
      if (a & 1) continue;
      a >>= 1;
    }
    for (int delta = -1; delta <= 1; ++delta) {
      const uint64_t n = (uint64_t)a + delta;
      if ((n >> (nb - 1)) == 1) check(n, m << qb);
    }
  }
}

}  // namespace fxr::div_ties
