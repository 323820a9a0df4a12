#include "axis_ticks.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string_view>

namespace tumble::plot {
namespace {

// Slack when deciding whether a value sits on a tick or a limit: i·step and log10 are off by a
// few ulps, never by a billionth of a step or a decade.
constexpr double kSlack = 1e-9;

// At most this many linear ticks, and at least this many when the room allows: fewer carry too
// little, more read as a ruler.
constexpr int kMaxLinearTicks = 8;
constexpr int kMinLinearTicks = 3;

// At most this many decade labels: a span of up to 8 decades is labelled at every decade, a
// longer one at every 2nd, 3rd, … decade.
constexpr int kMaxLogLabels = 9;

// Minor ticks (2..9 within a decade) only when a decade is at least this long: closer, the eight
// marks merge into a smudge.
constexpr double kMinDecadeForMinorPx = 40.0;

// Exponents beyond these make 10^e overflow or go subnormal: data there is clamped to them.
constexpr int kMinExponent = -300;
constexpr int kMaxExponent = 300;

double pow10(int exponent) {
  return std::pow(10.0, exponent);
}

std::optional<double> usable_limit(const std::optional<double>& limit, Scale scale) {
  if (!limit || !std::isfinite(*limit)) return std::nullopt;
  if (scale == Scale::Log10 && *limit <= 0.0) return std::nullopt;
  return limit;
}

// "2.50e-05" → "2.5e-5", "1.0e+06" → "1e6".
std::string compact_scientific(std::string_view text) {
  const std::size_t e = text.find('e');
  std::string mantissa(text.substr(0, e));
  if (mantissa.find('.') != std::string::npos) {
    while (mantissa.back() == '0') mantissa.pop_back();
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  std::string_view exponent = text.substr(e + 1);
  const bool negative = exponent.front() == '-';
  exponent.remove_prefix(1);  // the sign to_chars always writes
  while (exponent.size() > 1 && exponent.front() == '0') exponent.remove_prefix(1);
  return mantissa + "e" + (negative ? "-" : "") + std::string(exponent);
}

// A linear tick's label, with as many digits as the step needs and no more: a step of 0.25
// (exponent -2) prints 0.25, 0.50, 0.75; of 5e-6, 2.5e-5.
std::string linear_label(double value, int step_exponent, bool scientific) {
  std::array<char, 64> buf{};
  if (!scientific) {
    const int decimals = std::max(0, -step_exponent);
    const auto end = std::to_chars(buf.data(), buf.data() + buf.size(), value,
                                   std::chars_format::fixed, decimals)
                         .ptr;
    return {buf.data(), end};
  }
  if (value == 0.0) return "0";
  const int value_exponent = static_cast<int>(std::floor(std::log10(std::abs(value)) + kSlack));
  const int digits = std::clamp(value_exponent - step_exponent, 0, 15);
  const auto end = std::to_chars(buf.data(), buf.data() + buf.size(), value,
                                 std::chars_format::scientific, digits)
                       .ptr;
  return compact_scientific({buf.data(), static_cast<std::size_t>(end - buf.data())});
}

// Pads a range of zero width (or one inverted by a single given limit) so it can be drawn.
void pad_degenerate(double& lo, double& hi, bool lo_given, bool hi_given) {
  if (hi > lo) return;
  if (lo_given && hi_given && lo > hi) {
    std::swap(lo, hi);
    return;
  }
  // The given limit is the one to keep; with none given, lo == hi is the single data value.
  const double centre = lo_given ? lo : hi;
  const double pad = centre != 0.0 ? 0.1 * std::abs(centre) : 1.0;
  if (lo_given && !hi_given) {
    hi = centre + 2.0 * pad;
  } else if (hi_given && !lo_given) {
    lo = centre - 2.0 * pad;
  } else {
    lo = centre - pad;
    hi = centre + pad;
  }
}

AxisTicks linear_ticks(const Axis& axis, std::optional<DataExtent> data, TickRoom room) {
  const std::optional<double> given_lo = usable_limit(axis.min, Scale::Linear);
  const std::optional<double> given_hi = usable_limit(axis.max, Scale::Linear);
  double lo = given_lo ? *given_lo : data ? data->min : 0.0;
  double hi = given_hi ? *given_hi : data ? data->max : 1.0;
  pad_degenerate(lo, hi, given_lo.has_value(), given_hi.has_value());
  // ±1e307 keeps hi − lo finite whatever the data.
  lo = std::max(lo, -1e307);
  hi = std::min(hi, 1e307);

  const int room_ticks = static_cast<int>(room.length_px / room.min_label_spacing_px) + 1;
  const int max_ticks = std::clamp(room_ticks, kMinLinearTicks, kMaxLinearTicks);
  const double span = hi - lo;
  // Candidates 1, 2, 5 × 10^k from a tenth of the even split upwards; the first that fits at most
  // max_ticks ticks (after rounding the free limits outwards) wins. Twelve candidates span four
  // decades, far more than the rounding can need.
  constexpr std::array<int, 3> kMantissas = {1, 2, 5};
  const int first_exponent =
      static_cast<int>(std::floor(std::log10(span / static_cast<double>(max_ticks)))) - 1;
  double step = 0.0, first = 0.0, last = 0.0;
  int step_exponent = 0;
  for (int i = 0; i < 12; ++i) {
    step_exponent = first_exponent + i / 3;
    step = kMantissas[static_cast<std::size_t>(i % 3)] * pow10(step_exponent);
    first = given_lo ? std::ceil(lo / step - kSlack) : std::floor(lo / step + kSlack);
    last = given_hi ? std::floor(hi / step + kSlack) : std::ceil(hi / step - kSlack);
    if (last - first + 1.0 <= max_ticks) break;
  }
  // Tick i is i·step, never an accumulated sum, so 0.1-steps print 0.3 and not 0.30000000000000004.
  if (!given_lo) lo = first * step;
  if (!given_hi) hi = last * step;

  const double largest = std::max(std::abs(first * step), std::abs(last * step));
  const bool scientific = step_exponent < -4 || largest >= 1e6;
  AxisTicks result{lo, hi, {}};
  for (double i = first; i <= last; i += 1.0) {
    // i == 0 gives +0 (ceil of a small negative is −0, which would print "-0.0").
    const double value = i == 0.0 ? 0.0 : std::clamp(i * step, lo, hi);
    result.ticks.push_back({value, linear_label(value, step_exponent, scientific), true});
  }
  return result;
}

AxisTicks log_ticks(const Axis& axis, std::optional<DataExtent> data, TickRoom room) {
  const std::optional<double> given_lo = usable_limit(axis.min, Scale::Log10);
  const std::optional<double> given_hi = usable_limit(axis.max, Scale::Log10);
  const auto clamp_decades = [](double v) {
    return std::clamp(v, pow10(kMinExponent), pow10(kMaxExponent));
  };
  double lo = clamp_decades(given_lo ? *given_lo : data ? data->min : 1.0);
  double hi = clamp_decades(given_hi ? *given_hi : data ? data->max : 10.0);
  // Free limits go out to whole decades.
  if (!given_lo) lo = pow10(static_cast<int>(std::floor(std::log10(lo) + kSlack)));
  if (!given_hi) hi = pow10(static_cast<int>(std::ceil(std::log10(hi) - kSlack)));
  if (!(hi > lo)) {
    // As on a linear axis: keep the given limit and put two decades on the free side; with both
    // or neither given (a single value on a decade), one decade either side.
    if (given_lo && given_hi && lo > hi) {
      std::swap(lo, hi);
    } else if (given_lo && !given_hi) {
      hi = lo * 100.0;
    } else if (given_hi && !given_lo) {
      lo = hi / 100.0;
    } else {
      lo /= 10.0;
      hi *= 10.0;
    }
  }

  const double lo_decades = std::log10(lo), hi_decades = std::log10(hi);
  const int first = static_cast<int>(std::ceil(lo_decades - kSlack));
  const int last = static_cast<int>(std::floor(hi_decades + kSlack));
  const double decade_px = room.length_px / (hi_decades - lo_decades);

  // Label every k-th decade: at most kMaxLogLabels labels, no closer than the room allows.
  // Labelled exponents are multiples of k, so a plot from 1e-12 to 1e6 reads 1e-12, 1e-9, 1e-6,
  // 1e-3, 1, 1000, 1e6.
  const auto multiples_of = [first, last](int k) {
    int n = 0;
    for (int e = first; e <= last; ++e) n += e % k == 0 ? 1 : 0;
    return n;
  };
  constexpr std::array<int, 9> kLabelEvery = {1, 2, 3, 5, 10, 20, 50, 100, 200};
  int every = kLabelEvery.back();
  for (const int k : kLabelEvery) {
    if (multiples_of(k) <= kMaxLogLabels && decade_px * k >= room.min_label_spacing_px) {
      every = k;
      break;
    }
  }
  AxisTicks result{lo, hi, {}};
  const auto inside = [&](double v) { return v >= lo * (1 - kSlack) && v <= hi * (1 + kSlack); };
  for (int e = first; e <= last; ++e) {
    const bool labelled = e % every == 0;
    result.ticks.push_back({std::clamp(pow10(e), lo, hi), labelled ? log_label(1, e) : "", true});
  }
  if (decade_px >= kMinDecadeForMinorPx) {
    // Two decade ticks or fewer (a range of about one decade): label the minors too, or the
    // axis hardly reads as a scale. 2 and 5 when that gives three labels in all, else all.
    const bool few_decades = last - first < 2;
    int labelled_minors_2_5 = 0;
    for (int e = first - 1; e <= last; ++e)
      for (const int m : {2, 5}) labelled_minors_2_5 += inside(m * pow10(e)) ? 1 : 0;
    const bool only_2_5 = labelled_minors_2_5 + (last - first + 1) >= 3;
    for (int e = first - 1; e <= last; ++e) {
      for (int m = 2; m <= 9; ++m) {
        const double v = m * pow10(e);
        if (!inside(v)) continue;
        const bool labelled = few_decades && (!only_2_5 || m == 2 || m == 5);
        result.ticks.push_back({std::clamp(v, lo, hi), labelled ? log_label(m, e) : "", false});
      }
    }
    std::stable_sort(result.ticks.begin(), result.ticks.end(),
                     [](const Tick& a, const Tick& b) { return a.value < b.value; });
  }
  return result;
}

}  // namespace

AxisTicks axis_ticks(const Axis& axis, std::optional<DataExtent> data, TickRoom room) {
  // Callers pass only usable points; this keeps a stray NaN or a non-positive log value from
  // reaching log10 all the same.
  if (data && !(std::isfinite(data->min) && std::isfinite(data->max) && data->min <= data->max))
    data.reset();
  if (data && axis.scale == Scale::Log10 && data->min <= 0.0) data.reset();
  return axis.scale == Scale::Log10 ? log_ticks(axis, data, room) : linear_ticks(axis, data, room);
}

std::string log_label(int mantissa, int exponent) {
  const std::string m = std::to_string(mantissa);
  // 0.01 … 9000 read at a glance; beyond, the zeros would need counting.
  if (exponent >= 0 && exponent <= 3)
    return m + std::string(static_cast<std::size_t>(exponent), '0');
  if (exponent < 0 && exponent >= -2)
    return "0." + std::string(static_cast<std::size_t>(-exponent - 1), '0') + m;
  return m + "e" + std::to_string(exponent);
}

}  // namespace tumble::plot
