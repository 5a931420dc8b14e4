#include <cstdio>
int main() { std::puts("dotvision"); return 0; }
