// Polyphase resampling as scipy.signal.resample_poly does it.
//
// librosa.load(sr=22050, res_type="polyphase") resamples with scipy.signal.resample_poly, so
// reproducing it here lets the onset detector see the same samples as the librosa reference.
#pragma once

#include <memory>
#include <vector>

namespace gmg::audio {

// scipy.signal.resample_poly(x, up, down) with up/down = to_rate/from_rate in
// lowest terms, window ('kaiser', 5.0), zero padding. Output sample n lies at
// time n / to_rate (zero phase); the output has ceil(len(x) * up / down)
// samples. Returns a copy when the rates are equal. Throws gmg::Error when a
// rate is not positive or the filter would exceed 3.84 M taps (the larger of
// the reduced rates above 192000).
std::vector<float> resample_poly(const std::vector<float>& x, int from_rate, int to_rate);

// resample_poly's output a stretch at a time, for a reader that uses it as it goes (the onset
// analysis) rather than holding all of it: the same samples, bit for bit, however it is cut.
// x must outlive the resampler.
class PolyphaseResampler {
 public:
  // Throws gmg::Error as resample_poly does.
  PolyphaseResampler(const std::vector<float>& x, int from_rate, int to_rate);
  ~PolyphaseResampler();
  PolyphaseResampler(const PolyphaseResampler&) = delete;
  PolyphaseResampler& operator=(const PolyphaseResampler&) = delete;

  // Output samples in all: ceil(len(x) * up / down).
  long long size() const;
  // Outputs computed together: a stretch starts at a multiple of it.
  long long block() const;
  // Outputs n .. n + count - 1 into out[0 .. count): n a multiple of block(), and n + count a
  // multiple of it too or size().
  void compute(long long n, long long count, float* out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The filter design behind it (exposed for tests).

// Zeroth-order modified Bessel function of the first kind, I0(x), for |x| up to about 10.
double bessel_i0(double x);

// scipy.signal.firwin(numtaps, cutoff, window=('kaiser', beta)) for a
// low-pass with cutoff relative to Nyquist, scaled to unit gain at DC.
// numtaps >= 1; symmetric (linear phase).
std::vector<double> firwin_kaiser(int numtaps, double cutoff, double beta);

}  // namespace gmg::audio
