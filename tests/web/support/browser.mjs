// Debian's chromium, headless, driven by playwright-core, for the browser tests: one page at the
// tests' viewport whose uncaught errors are collected.
const { chromium } = await import(process.env.PLAYWRIGHT_CORE ?? 'playwright-core');

/** Launches the browser; returns { browser, page, pageErrors }. */
export async function openPage() {
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    headless: true,
    // Software WebGL: Chromium no longer falls back to SwiftShader on its own.
    args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking',
      '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
  const page = await browser.newPage({ viewport: { width: 1280, height: 960 } });
  const pageErrors = [];
  page.on('pageerror', (error) => pageErrors.push(error.message));
  return { browser, page, pageErrors };
}
