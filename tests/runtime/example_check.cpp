// Compares the effects the host example (examples/host) drew into its own frame with those
// `motionfx render` drew into the program's frame of the same scene, camera, size and frame
// (tests/runtime/example_matches_render.cmake runs both).
//
// The two pictures under the effects differ (the host shades its floor and character its own
// way), so the frames cannot be compared as they are. The effects are a premultiplied layer
// (L, a) over the picture, out = L + (1 - a) under, in linear light. The host example is run twice
// over the same depth: as it draws (F1 over its picture C1) and with its colours black (F2 = L over
// black). Per pixel that gives the example's layer: L = F2 and a = 1 - (F1 - F2) / C1 (from the
// channel where C1 is largest). Laid over the program's own picture without effects (Cp,
// `render --layers`) it must give the program's frame Fp:
//     predicted = L + (1 - a) Cp  ~  Fp,
// compared as 8-bit sRGB levels over the pixels where either side has effects. Pixels where a
// picture is clipped at 1 (the additive lines are brighter than white before the clamp) say
// nothing of the layer and are left out, counted.
//
//   motionfx_example_check HOST.ppm HOST_UNDER.ppm HOST_BLACK.ppm PROGRAM.png PROGRAM_UNDER.png
//
// Exit 0 when, away from the host picture's silhouettes, the share of compared pixels within
// kLevels levels is at least kShare, and over all compared pixels at least kShareAll.
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

// A level or two comes from each picture's own 8-bit rounding, magnified where C1 is dark (a is a
// quotient by it). Rasterisation differs at the silhouettes: the program tests its effects
// against four depths a pixel (its MSAA scene), the example against its one single-sampled depth,
// and the two draw the character's edges with their own antialiasing; there a pixel may differ by
// as much as an effect's whole colour. A silhouette pixel is one whose 3x3 neighbourhood in the
// host's or the program's picture without effects spans more than kEdgeLevels levels in a channel
// (both shade their flat parts smoothly).
constexpr int kLevels = 6;
constexpr double kShare = 0.995;
constexpr double kShareAll = 0.95;
constexpr int kEdgeLevels = 24;

struct Picture {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb; // 3 bytes a pixel, sRGB-encoded
};

bool readPpm(const std::string& path, Picture& out) {
    std::ifstream file(path, std::ios::binary);
    std::string magic;
    int maxValue = 0;
    if (!(file >> magic >> out.width >> out.height >> maxValue) || magic != "P6" ||
        maxValue != 255 || out.width <= 0 || out.height <= 0 || out.width > 16384 ||
        out.height > 16384)
        return false;
    file.get(); // the one whitespace after the header
    out.rgb.resize(size_t(out.width) * size_t(out.height) * 3);
    return bool(
        file.read(reinterpret_cast<char*>(out.rgb.data()), std::streamsize(out.rgb.size())));
}

bool readPng(const std::string& path, Picture& out) {
    int channels = 0;
    unsigned char* pixels = stbi_load(path.c_str(), &out.width, &out.height, &channels, 3);
    if (pixels == nullptr) return false;
    out.rgb.assign(pixels, pixels + size_t(out.width) * size_t(out.height) * 3);
    stbi_image_free(pixels);
    return true;
}

double decode(unsigned char v) {
    const double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double encode(double linear) {
    const double c = std::clamp(linear, 0.0, 1.0);
    return 255.0 * (c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055);
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 6) {
        std::fprintf(stderr, "usage: motionfx_example_check HOST.ppm HOST_UNDER.ppm "
                             "HOST_BLACK.ppm PROGRAM.png PROGRAM_UNDER.png\n");
        return 2;
    }
    Picture host, hostUnder, hostBlack, program, programUnder;
    const bool read = readPpm(argv[1], host) && readPpm(argv[2], hostUnder) &&
                      readPpm(argv[3], hostBlack) && readPng(argv[4], program) &&
                      readPng(argv[5], programUnder);
    if (!read) {
        std::fprintf(stderr, "motionfx_example_check: a picture could not be read\n");
        return 2;
    }
    for (const Picture* p : {&hostUnder, &hostBlack, &program, &programUnder})
        if (p->width != host.width || p->height != host.height) {
            std::fprintf(stderr, "motionfx_example_check: the pictures differ in size\n");
            return 2;
        }

    // The silhouettes of both pictures.
    const int w = host.width, h = host.height;
    std::vector<unsigned char> edge(size_t(w) * size_t(h), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                for (const Picture* under : {&hostUnder, &programUnder}) {
                    int low = 255, high = 0;
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            const size_t nx = size_t(std::clamp(x + dx, 0, w - 1));
                            const size_t ny = size_t(std::clamp(y + dy, 0, h - 1));
                            const int v = under->rgb[(ny * size_t(w) + nx) * 3 + size_t(c)];
                            low = std::min(low, v);
                            high = std::max(high, v);
                        }
                    if (high - low > kEdgeLevels) edge[size_t(y) * size_t(w) + size_t(x)] = 1;
                }
            }

    size_t effects = 0, clipped = 0, compared = 0, within = 0, hostOnly = 0, programOnly = 0;
    size_t inner = 0, innerWithin = 0;
    double sum = 0.0;
    int largest = 0;
    for (size_t p = 0; p < host.rgb.size(); p += 3) {
        bool hostHas = false, programHas = false, clip = false;
        for (size_t c = p; c < p + 3; ++c) {
            hostHas = hostHas || std::abs(host.rgb[c] - hostUnder.rgb[c]) > 2;
            programHas = programHas || std::abs(program.rgb[c] - programUnder.rgb[c]) > 2;
            clip = clip || host.rgb[c] >= 250 || hostBlack.rgb[c] >= 250 || program.rgb[c] >= 250;
        }
        if (!hostHas && !programHas) continue;
        ++effects;
        if (hostHas && !programHas) ++hostOnly;
        if (programHas && !hostHas) ++programOnly;
        if (clip) {
            ++clipped;
            continue;
        }
        size_t key = p;
        for (size_t c = p + 1; c < p + 3; ++c)
            if (hostUnder.rgb[c] > hostUnder.rgb[key]) key = c;
        const double under = decode(hostUnder.rgb[key]);
        const double alpha =
            under > 0.0
                ? std::clamp(1.0 - (decode(host.rgb[key]) - decode(hostBlack.rgb[key])) / under,
                             0.0, 1.0)
                : 0.0;
        int worst = 0;
        for (size_t c = p; c < p + 3; ++c) {
            const double predicted =
                encode(decode(hostBlack.rgb[c]) + (1.0 - alpha) * decode(programUnder.rgb[c]));
            worst = std::max(worst, int(std::lround(std::abs(predicted - program.rgb[c]))));
        }
        ++compared;
        sum += worst;
        largest = std::max(largest, worst);
        if (worst <= kLevels) ++within;
        if (!edge[p / 3]) {
            ++inner;
            if (worst <= kLevels) ++innerWithin;
        }
    }
    const double share = compared > 0 ? double(within) / double(compared) : 0.0;
    const double innerShare = inner > 0 ? double(innerWithin) / double(inner) : 0.0;
    std::printf("pixels with effects: %zu of %d (only in the example's: %zu, only in the "
                "program's: %zu); clipped at white, left out: %zu\n",
                effects, host.width * host.height, hostOnly, programOnly, clipped);
    std::printf("compared: %zu; within %d levels: %.2f%% (at least %.1f%% needed); mean %.2f, "
                "largest %d levels\n",
                compared, kLevels, 100.0 * share, 100.0 * kShareAll,
                compared > 0 ? sum / double(compared) : 0.0, largest);
    std::printf("away from the silhouettes: %zu compared; within %d levels: %.2f%% (at least "
                "%.1f%% needed)\n",
                inner, kLevels, 100.0 * innerShare, 100.0 * kShare);
    // Effects must be there to compare: a frame with almost none proves nothing.
    if (compared < size_t(host.width * host.height) / 100) {
        std::fprintf(stderr, "motionfx_example_check: under 1%% of the frame has effects to "
                             "compare\n");
        return 1;
    }
    return share >= kShareAll && innerShare >= kShare ? 0 : 1;
}
