// Replaced by the CLI (issue 2); kept minimal so the skeleton links.
#include <cstdio>
int main() { std::puts("kiri 0.1.0"); return 0; }
