// The lower body array L(k) and its powers L^t(k) (doc/method.md 1, eq. 4.2.1).
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace mbk {

// `lower` holds L(1..N) at indices 0..N-1 (the chapter's numbering is 1-based; body k is
// lower[k-1]). Throws std::invalid_argument with a one-line message naming the offending body
// when the array is empty or some L(k) is not in 0..k-1.
void validate_lower_body_array(const std::vector<int>& lower);

// L^t(k) for a valid array; L^0(k) = k; 0 once the chain has reached R.
int lower_body_power(const std::vector<int>& lower, int k, int t);

// Number of rows of the lower body arrays table: the greatest depth plus one (the all-zero row).
int lower_body_table_rows(const std::vector<int>& lower);

// The table row by row in O(N) memory: calls row(t, L^t) for t = 0 .. rows - 1, where L^t
// holds L^t(k) for k = 1..N (eq. 4.2.1: L^t(k) = L(L^(t-1)(k))).
void for_each_lower_body_row(const std::vector<int>& lower,
                             const std::function<void(int, const std::vector<int>&)>& row);

// The lower body arrays table (Tables 4.2.1, 4.2.2): row t holds L^t(k) for k = 1..N;
// rows t = 0,1,... until a row is all zeros (that row included). N x depth in memory: for
// big models use for_each_lower_body_row.
std::vector<std::vector<int>> lower_body_table(const std::vector<int>& lower);

// True iff body j (0 = R) is body k itself or one of its ancestors: j = L^t(k) for some t.
bool is_ancestor_or_self(const std::vector<int>& lower, int j, int k);

}  // namespace mbk
