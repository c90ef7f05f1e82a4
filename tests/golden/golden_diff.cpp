// Compares two files byte for byte; on a difference prints the first differing line of each
// and exits 1. Usage: golden_diff EXPECTED ACTUAL
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

static bool read(const char* path, std::string& out) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return false;
    std::ostringstream ss;
    ss << f.rdbuf();
    out = ss.str();
    return true;
}

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: golden_diff EXPECTED ACTUAL\n";
        return 2;
    }
    std::string e, a;
    if (!read(argv[1], e)) {
        std::cerr << "missing golden file " << argv[1] << " (run scripts/update-golden and review it)\n";
        return 1;
    }
    if (!read(argv[2], a)) {
        std::cerr << "missing output " << argv[2] << "\n";
        return 1;
    }
    if (e == a) return 0;
    std::istringstream es(e), as(a);
    std::string el, al;
    for (int line = 1;; ++line) {
        bool he = static_cast<bool>(std::getline(es, el)), ha = static_cast<bool>(std::getline(as, al));
        if (!he && !ha) break;
        if (!he) el = "<end of file>";
        if (!ha) al = "<end of file>";
        if (el != al || he != ha) {
            std::cerr << argv[2] << " differs from " << argv[1] << " at line " << line << ":\n  expected: " << el
                      << "\n  actual:   " << al << "\n";
            return 1;
        }
    }
    std::cerr << argv[2] << " differs from " << argv[1] << " in line endings or trailing bytes\n";
    return 1;
}
